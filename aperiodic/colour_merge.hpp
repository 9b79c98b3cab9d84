#pragma once
// Merging two colours of a corner set, kept only when the merge provably keeps aperiodicity
// (a search step of aperiodic/steps.hpp). A corner tiling is a colouring of the lattice points
// (pegs) whose every 2x2 window is a tile; merging colours x and y into one (x) maps the tilings of
// R onto colourings of the merged set R', peg by peg (pi). pi is a sliding block code, so it
// commutes with translations, but R' may have tilings that are no image, or images of two tilings.
//
// The check: a recovery map phi that puts a colour back from the pegs around each peg, within a
// radius r (the (2r+1) x (2r+1) neighbourhood; r = 1: the 3x3 pegs).
//   V(Q)   for a neighbourhood Q of R' whose centre is the merged colour: the colours v in {x, y}
//          such that some patch of R with centre v maps onto Q (other centres: V(Q) = {centre});
//   phi    recolours each peg with the member of V of its neighbourhood (x first when both).
// Every window of phi(c), for c a tiling of R', depends only on the (2r+2) x (2r+2) pegs around it.
// Such a patch of a tiling is the middle of a valid patch m pegs wider on each side (margin m >= 0):
// every such middle of R' (every window in R') is enumerated and the window phi gives it is checked
// to be a tile of R. V too is computed from the middles of valid patches of R, m wider (a tiling's
// neighbourhoods are such middles). When the check holds:
//   - pi(phi(c)) = c for every tiling c of R' (phi only puts x or y where c has x), so pi maps the
//     tilings of R onto those of R', and a periodic tiling c of R' gives the periodic tiling phi(c)
//     of R (phi commutes with translations): label `lifts`; R' is aperiodic when R is;
//   - if moreover every V(Q) met in the check has one member, then phi(pi(t)) = t for every
//     tiling t of R (pi(t) is a tiling of R', so its neighbourhoods are met in the check; the
//     patch of t around a peg is one of the middles V(Q) was computed from, so t's colour is the
//     only member), and pi is a bijection whose inverse phi is a sliding block code: label
//     `conjugate`.
// The check is sufficient, not necessary (patches that occur in no tiling of R' are checked too;
// a larger margin leaves out more of them).
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "tilesets/tile.hpp"

namespace tilekit {

inline constexpr int kMaxMergeRadius = 2;
inline constexpr int kMaxMergeMargin = 2;

struct ColourMerge {
  Colour kept = 0, merged = 0;  // merged becomes kept
  int radius = 1;               // of the neighbourhood that gives the colour back
  int margin = 0;               // of the valid patches the checked patches lie in
  bool conjugate = false;       // else lifts
};

// The result of merging `merged` into `kept` (tiles sorted, duplicates gone), or nullopt when the
// check above at this radius (1..kMaxMergeRadius) and margin (0..kMaxMergeMargin) fails (with
// allow_lifts false: unless it proves a conjugacy), when a colour exceeds 16 bits, or when R' has
// more than max_patches valid patches to enumerate.
std::optional<std::vector<CornerTile>> merge_colours(const std::vector<CornerTile>& tiles, Colour kept, Colour merged,
                                                     bool allow_lifts, int radius = 1, int margin = 0,
                                                     bool* conjugate = nullptr, std::size_t max_patches = 2000000);

// Sequences of checked merges, best first (fewest tiles, then fewest colours) over the partitions
// of the colours they reach, expanding at most max_expansions sets; each merge at the least radius
// that passes, then the least margin (past radius 1, margin 0 only for merges that save tiles at
// once). The least set reached.
struct MergeSearch {
  std::vector<CornerTile> tiles;    // the least set (the input when no merge applies)
  std::vector<ColourMerge> merges;  // the merges that lead to it, in order (input colour names)
  bool conjugate = true;            // every merge on the way proves a conjugacy
  std::size_t sets = 0;             // sets reached
  std::string argument() const;     // one line for the conversion's argument
};
MergeSearch least_colour_merge(const std::vector<CornerTile>& tiles, bool allow_lifts, int max_radius = 1,
                               int max_margin = 0, std::size_t max_expansions = 200);

// phi applied to a rectangle of pegs of R' (rows of colours, every window a tile of R'): the pegs
// whose neighbourhood, margin pegs wider, lies inside, recoloured (so 2 (radius + margin) rows and
// columns fewer). Used by the round-trip tests; throws std::invalid_argument where V is empty.
std::vector<std::vector<Colour>> recover_pegs(const std::vector<CornerTile>& source, Colour kept, Colour merged,
                                              int radius, int margin, const std::vector<std::vector<Colour>>& pegs);

}  // namespace tilekit
