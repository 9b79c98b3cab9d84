// The problem helpers of problem.hpp: the complete packing problem and the size check.
#include "solver/problem.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "base/error.hpp"
#include "solver/model.hpp"
#include "tilesets/window_torus.hpp"

namespace tilekit {

TilingProblem complete_packing_problem(TileKind kind, std::int64_t colours) {
  check_complete_set_colours(colours);
  TilingProblem p;
  const auto c = std::uint32_t(colours);
  p.set = kind == TileKind::Wang ? complete_wang_set(c, c) : complete_corner_set(c);
  p.rows = p.cols = int(c * c);
  p.torus = true;
  p.packing = true;
  return p;
}

TilingProblem window_torus_problem(std::int64_t colours, int window_rows, int window_cols, int rows, int cols) {
  check_colour_count(colours, "--colors");
  check_window_torus_shape(std::uint32_t(colours), window_rows, window_cols, rows, cols);
  TilingProblem p;
  p.set = complete_window_set(std::uint32_t(colours), window_rows, window_cols);
  p.rows = rows, p.cols = cols;
  p.torus = p.packing = true;
  return p;
}

void check_searchable(const TilingProblem& p) {
  const TileSet& set = p.set;
  if (set.kind() == TileKind::Window) return;  // the window model sizes itself (window_model.cpp)
  const std::uint64_t labels = set.kind() == TileKind::Corner
                                   ? std::uint64_t(set.horizontal_radix()) * set.horizontal_radix()
                                   : std::max(set.horizontal_radix(), set.vertical_radix());
  const std::uint64_t words = 4 * labels * ((set.size() + 63) / 64);
  if (words > kMaxModelTable)
    throw InputError(fmt::format(
        "{} is too large to search: {} tiles over {} edge labels need {} mask words (limit "
        "{}); a construction (--method construct) or fewer colours",
        set.name().empty() ? std::string("the tile set") : set.name(), set.size(), labels, words, kMaxModelTable));
}

}  // namespace tilekit
