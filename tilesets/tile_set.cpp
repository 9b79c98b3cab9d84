#include "tilesets/tile_set.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <set>

#include "base/error.hpp"

namespace tilekit {

namespace {

template <class T>
std::uint32_t distinct(const std::vector<T>& tiles, auto... members) {
  std::set<Colour> seen;
  for (const T& t : tiles) (seen.insert(t.*members), ...);
  return static_cast<std::uint32_t>(seen.size());
}

}  // namespace

void check_colour_count(std::int64_t c, const char* what) {
  if (c < 1 || c > 255) throw_input_error(what, fmt::format("{} must be between 1 and 255, got {}", what, c));
}

void check_complete_set_colours(std::int64_t c, const char* what) {
  if (c < 1 || c > std::int64_t(kMaxCompleteSetColours))
    throw_input_error(
        what, fmt::format("{} must be between 1 and {} for a packing or atlas of the complete set, got {}", what,
                          kMaxCompleteSetColours, c));
}

TileSet TileSet::wang(std::vector<WangTile> tiles, std::string name, std::string source, std::uint32_t ch,
                      std::uint32_t cv) {
  TileSet s;
  s.kind_ = TileKind::Wang;
  for (const WangTile& t : tiles) {
    ch = std::max({ch, t.n + 1, t.s + 1});
    cv = std::max({cv, t.e + 1, t.w + 1});
  }
  s.ch_ = std::max(ch, 1u);
  s.cv_ = std::max(cv, 1u);
  if (tiles.size() > kMaxTiles)
    throw InputError(fmt::format("{} tiles is more than the limit of {}", tiles.size(), kMaxTiles));
  s.wang_ = std::move(tiles);
  s.name_ = std::move(name);
  s.source_ = std::move(source);
  s.check_distinct();
  return s;
}

TileSet TileSet::corner(std::vector<CornerTile> tiles, std::string name, std::string source, std::uint32_t c) {
  TileSet s;
  s.kind_ = TileKind::Corner;
  for (const CornerTile& t : tiles) c = std::max({c, t.ne + 1, t.se + 1, t.sw + 1, t.nw + 1});
  s.ch_ = s.cv_ = std::max(c, 1u);
  if (s.ch_ > kMaxCornerColours)
    throw InputError(
        fmt::format("a corner set over {} colours is too large: tile indices (thesis eq. 2.5) are 32-bit, "
                    "so at most {} colours",
                    s.ch_, kMaxCornerColours));
  if (tiles.size() > kMaxTiles)
    throw InputError(fmt::format("{} tiles is more than the limit of {}", tiles.size(), kMaxTiles));
  s.corner_ = std::move(tiles);
  s.name_ = std::move(name);
  s.source_ = std::move(source);
  s.check_distinct();
  return s;
}

void TileSet::check_distinct() const {
  // Compared by colours, not by index: 32-bit indices of large colours can coincide.
  std::vector<std::pair<std::array<Colour, 4>, std::size_t>> tiles(size());
  for (std::size_t k = 0; k < size(); ++k) {
    auto c = file_colours(k);
    tiles[k] = {{c[0], c[1], c[2], c[3]}, k};
  }
  std::sort(tiles.begin(), tiles.end());
  auto dup = std::adjacent_find(tiles.begin(), tiles.end(), [](const auto& a, const auto& b) { return a.first == b.first; });
  if (dup != tiles.end())
    throw InputError(fmt::format("duplicate tile: tile {} repeats tile {} ({})", dup[1].second + 1, dup[0].second + 1,
                                 fmt::join(file_colours(dup[0].second), " ")));
}

const std::vector<WangTile>& TileSet::wang_tiles() const {
  if (kind_ != TileKind::Wang)
    throw InputError(fmt::format("tile set '{}' is a {} set, not a Wang set", name_, kind_name(kind_)));
  return wang_;
}

const std::vector<CornerTile>& TileSet::corner_tiles() const {
  if (kind_ != TileKind::Corner)
    throw InputError(fmt::format("tile set '{}' is a {} set, not a corner set", name_, kind_name(kind_)));
  return corner_;
}

std::uint32_t TileSet::horizontal_colours() const {
  return kind_ == TileKind::Wang ? distinct(wang_, &WangTile::n, &WangTile::s) : colours();
}

std::uint32_t TileSet::vertical_colours() const {
  return kind_ == TileKind::Wang ? distinct(wang_, &WangTile::e, &WangTile::w) : colours();
}

std::uint32_t TileSet::colours() const {
  if (kind_ == TileKind::Wang) return std::max(horizontal_colours(), vertical_colours());
  if (kind_ == TileKind::Window) return ch_;  // every window: every symbol occurs
  return distinct(corner_, &CornerTile::ne, &CornerTile::se, &CornerTile::sw, &CornerTile::nw);
}

TileIndex TileSet::index_of(std::size_t k) const {
  if (kind_ == TileKind::Window) return TileIndex(k);
  return kind_ == TileKind::Wang ? wang_index(wang_[k], ch_, cv_) : corner_index(corner_[k], ch_);
}

std::optional<std::size_t> TileSet::find_index(TileIndex i) const {
  if (kind_ == TileKind::Window) return i < window_count_ ? std::optional<std::size_t>(i) : std::nullopt;
  for (std::size_t k = 0; k < size(); ++k)
    if (index_of(k) == i) return k;
  return std::nullopt;
}

std::vector<Colour> TileSet::file_colours(std::size_t k) const {
  if (kind_ == TileKind::Window) {
    std::vector<Colour> digits(std::size_t(window_rows_) * std::size_t(window_cols_));
    for (std::size_t d = digits.size(); d-- > 0; k /= ch_) digits[d] = Colour(k % ch_);  // most significant first
    return digits;
  }
  if (kind_ == TileKind::Wang) {
    const WangTile& t = wang_[k];
    return {t.n, t.s, t.w, t.e};
  }
  const CornerTile& t = corner_[k];
  return {t.nw, t.ne, t.sw, t.se};
}

TileSet complete_wang_set(std::uint32_t ch, std::uint32_t cv) {
  check_colour_count(ch, "horizontal colours");
  check_colour_count(cv, "vertical colours");
  const std::uint64_t n = complete_size(ch, cv);
  if (n > (1u << 26))
    throw InputError(fmt::format("complete Wang set over {}x{} colours is too large ({} tiles)", ch, cv, n));
  std::vector<WangTile> tiles(n);
  for (TileIndex i = 0; i < n; ++i) tiles[i] = wang_tile(i, ch, cv);
  std::string name = ch == cv ? fmt::format("complete-wang-{}", ch) : fmt::format("complete-wang-{}x{}", ch, cv);
  return TileSet::wang(std::move(tiles), name, "complete Wang set (thesis sec. 2.7)", ch, cv);
}

TileSet complete_corner_set(std::uint32_t c) {
  check_colour_count(c);
  const std::uint64_t n = complete_size(c, c);
  if (n > (1u << 26))
    throw InputError(fmt::format("complete corner set over {} colours is too large ({} tiles)", c, n));
  std::vector<CornerTile> tiles(n);
  for (TileIndex i = 0; i < n; ++i) tiles[i] = corner_tile(i, c);
  return TileSet::corner(std::move(tiles), fmt::format("complete-corner-{}", c),
                         "complete corner set (thesis sec. 2.7)", c);
}

TileSet complete_window_set(std::uint32_t colours, int rows, int cols) {
  check_colour_count(colours);
  if (rows < 1 || cols < 1) throw InputError(fmt::format("a window needs at least 1x1 symbols, got {}x{}", rows, cols));
  std::uint64_t n = 1;
  for (int d = 0; d < rows * cols; ++d) {
    n *= colours;
    if (n > kMaxTiles)
      throw InputError(fmt::format("{}x{} windows over {} symbols are more than the limit of {} windows", rows, cols,
                                   colours, kMaxTiles));
  }
  TileSet s;
  s.kind_ = TileKind::Window;
  s.ch_ = s.cv_ = colours;
  s.window_rows_ = rows;
  s.window_cols_ = cols;
  s.window_count_ = std::size_t(n);
  s.name_ = fmt::format("complete-window-{}x{}-{}", rows, cols, colours);
  s.source_ = "every window of a de Bruijn torus (perfect map)";
  return s;
}

TileSet corner_to_wang(const TileSet& corner) {
  const std::uint32_t c = corner.horizontal_radix();
  std::vector<WangTile> tiles;
  tiles.reserve(corner.size());
  for (const CornerTile& t : corner.corner_tiles()) {
    // thesis sec. 2.9: a pair of corner colours becomes one edge colour
    tiles.push_back({t.nw * c + t.ne, t.ne * c + t.se, t.sw * c + t.se, t.nw * c + t.sw});
  }
  return TileSet::wang(std::move(tiles), corner.name().empty() ? "" : corner.name() + "-as-wang",
                       "corner set as Wang set (thesis sec. 2.9)", c * c, c * c);
}

}  // namespace tilekit
