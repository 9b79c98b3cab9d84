#include "tilesets/window_torus.hpp"

#include <fmt/format.h>

#include <cassert>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "base/error.hpp"
#include "tilesets/constructions.hpp"
#include "tilesets/reference_data.hpp"
#include "tilesets/tile_set.hpp"
#include "tilesets/validator.hpp"

namespace tilekit {

std::uint64_t window_count(std::uint32_t colours, int rows, int cols, std::uint64_t limit) {
  std::uint64_t n = 1;
  for (std::int64_t d = 0; d < std::int64_t(rows) * cols; ++d) {
    n *= colours;
    if (n > limit) return 0;
    if (n <= 1) break;  // C = 1: one window of any size
  }
  return n;
}

void check_window_torus_shape(std::uint32_t colours, int window_rows, int window_cols, int rows, int cols) {
  if (window_rows < 1 || window_cols < 1)
    throw RequestError("window", fmt::format("`window` {}x{}: a window needs K >= 1 rows and L >= 1 columns",
                                             window_rows, window_cols));
  if (window_rows > rows || window_cols > cols)
    throw RequestError("window",
                       fmt::format("`window` {}x{} is larger than the {}x{} torus (a window must fit in the torus)",
                                   window_rows, window_cols, rows, cols));
  const std::uint64_t n = window_count(colours, window_rows, window_cols, kMaxTiles);
  if (n == 0)
    throw InputError(fmt::format("{}x{} windows over {} symbols are more than {}^{} > {} windows (the limit)",
                                 window_rows, window_cols, colours, colours, window_rows * window_cols, kMaxTiles));
  if (std::uint64_t(rows) * std::uint64_t(cols) != n)
    throw RequestError(
        "size",
        fmt::format("`size` {}x{}: a torus holding each of the {}^({}*{}) = {} windows once has rows*cols = {}, not {}",
                    rows, cols, colours, window_rows, window_cols, n, n, std::uint64_t(rows) * std::uint64_t(cols)));
}

Tiling window_torus_from_pegs(const std::vector<Colour>& pegs, int rows, int cols, std::uint32_t colours,
                              int window_rows, int window_cols) {
  assert(pegs.size() == std::size_t(rows) * std::size_t(cols));
  Tiling t(TileKind::Window, colours, rows, cols, true);
  t.window_rows = window_rows;
  t.window_cols = window_cols;
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) {
      std::uint64_t i = 0;
      for (int a = 0; a < window_rows; ++a)
        for (int b = 0; b < window_cols; ++b)
          i = i * colours + pegs[std::size_t((r + a) % rows) * std::size_t(cols) + std::size_t((c + b) % cols)];
      t.at(r, c) = TileIndex(i);
    }
  return t;
}

std::vector<Colour> pegs_of_window_torus(const Tiling& t) {
  std::uint64_t top = 1;  // C^(KL-1): the weight of the top-left symbol
  for (int d = 1; d < t.window_rows * t.window_cols; ++d) top *= t.colours;
  std::vector<Colour> pegs(t.cells.size());
  for (std::size_t i = 0; i < t.cells.size(); ++i) pegs[i] = Colour(t.cells[i] / top % t.colours);
  return pegs;
}

Tiling window_torus_of_corner_torus(const Tiling& corner) {
  return window_torus_from_pegs(pegs_of_corner_torus(corner), corner.rows, corner.cols, corner.colours, 2, 2);
}

Tiling corner_torus_of_window_torus(const Tiling& window) {
  if (window.window_rows != 2 || window.window_cols != 2)
    throw InputError(fmt::format("a corner torus has 2x2 windows, not {}x{}", window.window_rows, window.window_cols));
  return corner_torus_from_pegs(pegs_of_window_torus(window), window.rows, window.cols, window.colours);
}

std::vector<Tiling> stored_window_tori(std::uint32_t colours, int window_rows, int window_cols) {
  std::vector<Tiling> out;
  const std::string prefix = fmt::format("window-{}x{}-{}-", window_rows, window_cols, colours);
  for (const EmbeddedFile& f : reference_data()) {
    if (f.name.rfind(prefix, 0) != 0) continue;
    const std::string name(f.name);
    Tiling t = tiling_from_json(nlohmann::json::parse(f.text), name);
    if (t.kind != TileKind::Window || t.colours != colours || t.window_rows != window_rows ||
        t.window_cols != window_cols || !validate(t).packing)
      throw std::logic_error(fmt::format("embedded {} is not the de Bruijn torus its name says", name));
    out.push_back(std::move(t));
  }
  return out;
}

std::optional<ConstructedWindowTorus> construct_window_torus(std::uint32_t colours, int window_rows, int window_cols,
                                                             int rows, int cols) {
  for (Tiling& t : stored_window_tori(colours, window_rows, window_cols))
    if (t.rows == rows && t.cols == cols) return ConstructedWindowTorus{std::move(t), "stored"};
  if (window_rows == 2 && window_cols == 2 && rows == int(colours * colours) && cols == rows)
    if (auto corner = construct_packing(TileKind::Corner, colours))
      return ConstructedWindowTorus{window_torus_of_corner_torus(corner->tiling), "corner " + corner->how};
  return std::nullopt;
}

Tiling window_colour_lift(const Tiling& base, const Tiling& quotient) {
  if (base.kind != TileKind::Window || quotient.kind != TileKind::Window || !base.torus || !quotient.torus)
    throw InputError("a window lift takes two window tori");
  if (base.window_rows != quotient.window_rows || base.window_cols != quotient.window_cols)
    throw InputError(fmt::format("the base has {}x{} windows, the quotient {}x{}", base.window_rows, base.window_cols,
                                 quotient.window_rows, quotient.window_cols));
  if (quotient.rows % base.rows != 0 || quotient.cols % base.cols != 0)
    throw InputError(fmt::format("the quotient's {}x{} torus is not a multiple of the base's {}x{}", quotient.rows,
                                 quotient.cols, base.rows, base.cols));
  const std::uint32_t m = base.colours, C = m * quotient.colours;
  const std::vector<Colour> b = pegs_of_window_torus(base), e = pegs_of_window_torus(quotient);
  std::vector<Colour> a(e.size());
  for (int i = 0; i < quotient.rows; ++i)
    for (int j = 0; j < quotient.cols; ++j) {
      const std::size_t at = std::size_t(i) * std::size_t(quotient.cols) + std::size_t(j);
      a[at] = b[std::size_t(i % base.rows) * std::size_t(base.cols) + std::size_t(j % base.cols)] + m * e[at];
    }
  return window_torus_from_pegs(a, quotient.rows, quotient.cols, C, base.window_rows, base.window_cols);
}

}  // namespace tilekit
