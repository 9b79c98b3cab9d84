// The problem helpers of problem.hpp: the complete packing problem and the size check.
#include "solver/problem.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <utility>

#include "base/error.hpp"
#include "solver/model.hpp"
#include "tilesets/window_torus.hpp"

namespace tilekit {

namespace {
constexpr std::pair<Formulation, std::string_view> kFormulationNames[] = {
    {Formulation::Auto, "auto"},   {Formulation::Cell, "cell"}, {Formulation::Pegs, "pegs"},
    {Formulation::Edges, "edges"}, {Formulation::Sat, "sat"},
};
}  // namespace

std::string_view formulation_name(Formulation f) {
  for (const auto& [g, name] : kFormulationNames)
    if (g == f) return name;
  return "?";
}

std::optional<Formulation> formulation_from_name(std::string_view name) {
  for (const auto& [f, word] : kFormulationNames)
    if (word == name) return f;
  return std::nullopt;
}

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
  check_colour_count(colours, "`colours`");
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
    throw RequestError(
        "method", fmt::format("{} is too large to search: {} tiles over {} edge labels need {} mask words (limit "
                              "{}); a construction (`method` construct) or fewer colours",
                              set.name().empty() ? std::string("the tile set") : set.name(), set.size(), labels, words,
                              kMaxModelTable));
}

}  // namespace tilekit
