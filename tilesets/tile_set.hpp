#pragma once
// Tile sets (thesis ch. 2): an ordered list of distinct Wang or corner tiles, with a name
// and a source line. The position of a tile in the list is its "tile number"; its index
// (thesis eq. 2.2/2.5) depends on the colour radix.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "tilesets/tile.hpp"

namespace tilekit {

// Limits (README, "Bad input"). Tile indices (thesis eq. 2.2 / 2.5) are 32-bit, so a corner
// set has at most 256 colours and a Wang set read from a file at most C_h * C_v = 65536 (then
// (C_h C_v)^2 - 1 is the largest index; Wang sets built in memory, such as the aperiodic
// tables' over hundreds of colours, are never indexed); a colour in a file is at most 65535. The largest set is 2^26 tiles
// (complete-corner-90, 1 GiB as Wang tiles), far above the largest set Tilekit builds from
// data (1.2 M tiles in the aperiodic tables).
inline constexpr std::int64_t kMaxTileSetColour = 65535;
inline constexpr std::uint64_t kMaxCornerColours = 256;
inline constexpr std::uint64_t kMaxWangColourProduct = 65536;
inline constexpr std::size_t kMaxTiles = std::size_t(1) << 26;

class TileSet {
 public:
  TileSet() = default;
  // Both factories reject duplicate tiles and sets beyond the limits above (InputError).
  // Colour radices default to max colour + 1 per direction; pass larger ones to declare
  // unused colours.
  static TileSet wang(std::vector<WangTile> tiles, std::string name = {}, std::string source = {},
                      std::uint32_t ch = 0, std::uint32_t cv = 0);
  static TileSet corner(std::vector<CornerTile> tiles, std::string name = {}, std::string source = {},
                        std::uint32_t c = 0);

  TileKind kind() const { return kind_; }
  std::size_t size() const {
    return kind_ == TileKind::Wang ? wang_.size() : kind_ == TileKind::Corner ? corner_.size() : window_count_;
  }
  // Window sets (complete_window_set()): the window's rows K and columns L; 0 for other sets.
  int window_rows() const { return window_rows_; }
  int window_cols() const { return window_cols_; }
  bool empty() const { return size() == 0; }
  const std::vector<WangTile>& wang_tiles() const;
  const std::vector<CornerTile>& corner_tiles() const;

  // Colour radix: N/S edges (ch) and E/W edges (cv) for Wang sets; both equal for corner sets.
  std::uint32_t horizontal_radix() const { return ch_; }
  std::uint32_t vertical_radix() const { return cv_; }
  // Distinct colours actually used, per direction and overall. The thesis reports
  // Wang sets as max(horizontal, vertical) (e.g. kari-14 is "14/6").
  std::uint32_t horizontal_colours() const;
  std::uint32_t vertical_colours() const;
  std::uint32_t colours() const;

  // Index of tile number k (thesis eq. 2.2 / 2.5, mixed radix for Wang sets).
  TileIndex index_of(std::size_t k) const;
  // Tile number of the tile with this index, if the set holds it.
  std::optional<std::size_t> find_index(TileIndex i) const;
  // The colours of tile k in file order: n s w e (Wang), nw ne sw se (corner), or the window's
  // K x L symbols row by row.
  std::vector<Colour> file_colours(std::size_t k) const;

  const std::string& name() const { return name_; }
  const std::string& source() const { return source_; }
  void set_name(std::string n) { name_ = std::move(n); }
  void set_source(std::string s) { source_ = std::move(s); }

 private:
  void check_distinct() const;
  TileKind kind_ = TileKind::Wang;
  std::vector<WangTile> wang_;
  std::vector<CornerTile> corner_;
  std::uint32_t ch_ = 0, cv_ = 0;
  int window_rows_ = 0, window_cols_ = 0;
  std::size_t window_count_ = 0;
  std::string name_, source_;
  friend TileSet complete_window_set(std::uint32_t colours, int rows, int cols);
};

// Complete sets: every combination of colours (thesis sec. 2.7, Fig. 2.4).
// Tiles are listed in index order, so tile number == tile index.
TileSet complete_wang_set(std::uint32_t ch, std::uint32_t cv);
TileSet complete_corner_set(std::uint32_t c);
// Every K x L window over C symbols (a perfect map's "tiles"), tile number == window index
// (tilesets/window_torus.hpp); nothing is stored per window. InputError beyond kMaxTiles windows.
TileSet complete_window_set(std::uint32_t colours, int rows, int cols);

// Corner set -> equivalent Wang set (thesis sec. 2.9): the pair of corner colours along an
// edge becomes one edge colour, pair (a, b) -> a*C + b read clockwise from the tile's
// first corner of that edge (N: nw,ne; E: ne,se; S: sw,se; W: nw,sw), so matching edges
// get equal colours. The result has C^2 colours and keeps the tile order.
TileSet corner_to_wang(const TileSet& corner);

// Checks 1 <= C <= 255 for the built-in families; throws InputError naming the parameter.
void check_colour_count(std::int64_t c, const char* what = "colours");

// The largest C whose complete set is packed (`pack`) or laid out as an atlas (`atlas lookup`,
// `texture atlas`): C^4 = 16.8 M tiles on a 4096 x 4096 torus, 64 MB of cells and as much again
// of positions; with tiles of at least 4 pixels a 16384-pixel texture, the largest most GPUs
// take. Beyond it building the set alone took minutes and gigabytes (larger C ended in
// std::bad_alloc) before a search that could never end.
inline constexpr std::uint32_t kMaxCompleteSetColours = 64;
// Checks 1 <= C <= kMaxCompleteSetColours; throws InputError naming `what` (by default the request
// field `colours`: a RequestError, base/error.hpp).
void check_complete_set_colours(std::int64_t c, const char* what = "`colours`");

}  // namespace tilekit
