#pragma once
// Conversions between aperiodic Wang and corner tile sets (thesis ch. 8):
//   Wang -> corner: DiagonalTranslation (8.3.1), HorizontalTranslation and
//   VerticalTranslation (8.3.2), Rotation with the checkerboard tiles (8.3.3),
//   Subdivision (8.3.4, optional colour merges); corner -> Wang: pair colours (8.4).
// Every result carries a soundness label (see Soundness) and the colour maps needed to
// carry a tiling of the source over to the result (aperiodic/maps.hpp).
//
// The conversions work on plain tile lists rather than TileSet, because the iterated
// tables (8.3-8.7) reach 10^6 tiles over 10^4 colours, beyond 32-bit tile indices.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "tilesets/tile_set.hpp"

namespace tilekit {

// What is known about a conversion result's relation to its source.
//   Conjugate:  tilings of the plane by the source and by the result are in bijection by a
//               translation-equivariant local map (argued per construction in the .cpp);
//               so the result is aperiodic exactly when the source is.
//   Lifts:      every tiling of the result lifts to a tiling of the source, row by row
//               (checked by automata, aperiodic/translation_lift.hpp). The source's tilings map onto
//               the result's, and a periodic tiling of the result lifts to a periodic
//               one of the source: aperiodicity is preserved, but the map may not be 1-1.
//   Unverified: neither is known; `aperiodic verify` may still find a periodic tiling.
//   Periodic:   a periodic tiling of the result has been found (verify).
enum class Soundness { Conjugate, Lifts, Unverified, Periodic };
std::string soundness_name(Soundness s);

enum class ConversionMethod { Diagonal, Horizontal, Vertical, Rotation, Subdivision, ToWang };
std::string method_name(ConversionMethod m);
// Throws InputError listing the valid names.
ConversionMethod parse_method(const std::string& name);

struct SubdivisionOptions {
  // Group the centre colours of Wang tiles whose quadrant tiles can share them without
  // admitting new tilings (checked exactly, see subdivision()); keeps `conjugate`.
  bool merge_centres = false;
  // Use an edge colour as the extra "star" colour (thesis 8.3.4, "the additional color can
  // be one of the edge colors"); this can admit tilings out of phase: `unverified`.
  bool star_is_edge_colour = false;
};

struct Conversion {
  ConversionMethod method = ConversionMethod::Diagonal;
  TileKind kind = TileKind::Corner;        // of the result
  std::vector<WangTile> wang;              // the result, when kind == Wang
  std::vector<CornerTile> corner;          // the result, when kind == Corner
  std::uint32_t colours = 0;               // corner: colours; Wang: max(horizontal, vertical)
  std::uint32_t horizontal_colours = 0, vertical_colours = 0;
  Soundness soundness = Soundness::Unverified;
  std::string argument;                    // one line: why this label
  std::size_t white = 0, black = 0;        // rotation: checkerboard tile counts (Table 8.1)

  // Colour maps from the source to the result (for aperiodic/maps.hpp). Entries are
  // kNoColour for source colours/tiles that the result does not use.
  static constexpr Colour kNoColour = ~Colour(0);
  std::vector<Colour> hmap, vmap;          // Wang source: N/S colour -> peg, E/W colour -> peg
  std::vector<Colour> tile_colour;         // diagonal/subdivision: source tile -> peg colour
  Colour star = kNoColour;                 // subdivision: the colour of the Wang vertices

  std::size_t size() const { return kind == TileKind::Wang ? wang.size() : corner.size(); }
};

// Colours relabelled to 0..k-1 in increasing order: per direction for Wang tiles (N/S and
// E/W separately, thesis 8.3: "relabeled to form an integer sequence starting with 0"),
// jointly for corner tiles. Tile order is kept.
std::vector<WangTile> relabel_wang(const std::vector<WangTile>& tiles);
std::vector<CornerTile> relabel_corner(const std::vector<CornerTile>& tiles);
TileSet relabel_colours(const TileSet& set);

// Distinct colours used: Wang (horizontal = N/S, vertical = E/W), corner (all four).
std::uint32_t wang_horizontal_colours(const std::vector<WangTile>& tiles);
std::uint32_t wang_vertical_colours(const std::vector<WangTile>& tiles);
std::uint32_t corner_colours(const std::vector<CornerTile>& tiles);

Conversion diagonal_translation(const std::vector<WangTile>& source);
// max_lift_states bounds the soundness check (aperiodic/translation_lift.hpp); 0 skips it (unverified).
Conversion horizontal_translation(const std::vector<WangTile>& source, std::size_t max_lift_states = 200000);
Conversion vertical_translation(const std::vector<WangTile>& source, std::size_t max_lift_states = 200000);
Conversion rotation(const std::vector<WangTile>& source);
Conversion subdivision(const std::vector<WangTile>& source, const SubdivisionOptions& opts = {});
Conversion corner_to_wang_pairs(const std::vector<CornerTile>& source);

// Dispatch on the method; checks the source kind (InputError if it does not fit) and
// that the source is not empty.
Conversion convert(const TileSet& source, ConversionMethod method, const SubdivisionOptions& opts = {});

// Soundness of a pruned translation result (`pruned` is a subset of conv.corner, e.g. from
// aperiodic/prune.hpp, which keeps aperiodicity): `lifts` when every row (column) of a
// tiling by `pruned` lifts to the source (so the pruned set is aperiodic if the source
// is); otherwise the conversion's own label. Other methods keep their label.
Soundness pruned_soundness(const std::vector<WangTile>& source, const Conversion& conv,
                           const std::vector<CornerTile>& pruned, std::string* argument = nullptr);

// The result as a TileSet (InputError if its colours exceed what 32-bit indices hold).
TileSet conversion_tile_set(const Conversion& c, const std::string& name, const std::string& source);

}  // namespace tilekit
