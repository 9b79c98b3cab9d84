#pragma once
// Tile sets up to symmetry: the images of a set under the dihedral group of the square (rotations,
// reflections, transposition), and a canonical form up to that group, colour relabelling and tile
// order, so that a search over conversions (aperiodic/enumerate.hpp) expands each set once.
//
// Two sets that differ by a rotation, a reflection or a renaming of colours have the same tilings
// up to that map, so they are periodic, aperiodic or finite together and have the same size.
// The canonical form is the least (as text) relabelled tile list over the 8 images; the
// relabelling is found by colour refinement with individualisation (the scheme of McKay's nauty,
// without automorphism pruning): colours are split by how they occur in tiles until every colour
// is alone in its class, branching where refinement alone leaves ties, and the least result is
// kept. A set with so many symmetric colours that the branches exceed a budget gets the least
// form found within it (`exact` false): still a relabelled copy of the set, so two sets with equal
// forms are always isomorphic; only the converse may fail (a duplicate is then expanded twice).
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "base/run_control.hpp"
#include "tilesets/tile_set.hpp"

namespace tilekit {

// The 8 symmetries of the square: first mirror left-right (when mirror), then rotate
// quarter-turns clockwise.
struct Dihedral {
  int quarter_turns = 0;  // 0..3
  bool mirror = false;
  std::string name() const;  // "id", "rot90", ..., "mirror", "mirror+rot90", ...
  static std::vector<Dihedral> all();
  // InputError for a name that is not one of all()'s.
  static Dihedral parse(const std::string& name);
};

// The image of a set under g: each tile moved by g (a Wang set's N/S and E/W colours swap roles
// under a quarter turn). Name and source are kept.
TileSet transform(const TileSet& set, const Dihedral& g);

struct CanonicalForm {
  TileSet set;        // colours relabelled densely (per direction for Wang sets), tiles sorted
  std::string text;   // "wang\n" or "corner\n", then one tile per line in file order
  std::string hash;   // 16 hex digits of FNV-1a 64 of text
  Dihedral from;      // canonical set == relabel(transform(input, from))
  bool exact = true;  // false: the branching budget was hit (see the header)
};

// Thrown by the canonical forms when their deadline passes (a set of thousands of tiles, whose
// refinement alone takes minutes): the caller reports how far it got.
struct CanonicalTimeLimit : std::runtime_error {
  CanonicalTimeLimit() : std::runtime_error("the time limit passed while computing a canonical form") {}
};

// Canonical form up to colour relabelling and tile order only (no dihedral images).
CanonicalForm relabel_canonical(const TileSet& set, std::size_t max_leaves = 512, const Deadline& deadline = {});
// Canonical form up to the dihedral group, colour relabelling and tile order.
CanonicalForm canonical_form(const TileSet& set, std::size_t max_leaves = 512, const Deadline& deadline = {});

// The set a canonical text describes (name enum-HASH). InputError naming `origin` when the text
// is not of that form (a kind line, then four colours per line).
TileSet set_from_canonical_text(const std::string& text, const std::string& origin);

}  // namespace tilekit
