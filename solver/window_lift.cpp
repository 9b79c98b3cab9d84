#include "solver/window_lift.hpp"

#include <fmt/format.h>

#include "base/error.hpp"
#include "tilesets/validator.hpp"
#include "tilesets/window_torus.hpp"

namespace tilekit {

namespace {

WindowLiftProblem row_difference_problem(const TilingProblem& problem, const std::string& text) {
  WindowLiftProblem p;
  p.row_difference = true;
  p.spec.base_file = text.substr(5);
  if (p.spec.base_file.empty())
    throw RequestError("lift", "`lift` rows=FILE: give the file of the torus of differences");
  try {
    p.base = read_tiling_file(p.spec.base_file);
  } catch (const InputError& e) {
    throw RequestError("lift", fmt::format("`lift` {}: {}", text, e.what()));
  }
  if (p.base.kind == TileKind::Corner && p.base.torus) p.base = window_torus_of_corner_torus(p.base);  // 2x2 windows
  p.base_how = p.spec.base_file;
  if (!validate(p.base).packing)
    throw RequestError("lift", fmt::format("`lift` {}: the base is not a de Bruijn torus", text));
  p.colours = problem.set.horizontal_radix();
  row_difference_ties(problem, p.base);  // checks that A fits (InputError)
  return p;
}

}  // namespace

SymbolTies window_lift_ties(const TilingProblem& problem, const WindowLiftProblem& lift) {
  return lift.row_difference ? row_difference_ties(problem, lift.base) : SymbolTies{};
}

WindowLiftProblem make_window_lift_problem(const TilingProblem& problem, const std::string& text) {
  if (text.rfind("rows=", 0) == 0) return row_difference_problem(problem, text);
  const LiftSpec spec = parse_lift_spec(text);
  const TileSet& set = problem.set;
  const std::uint32_t C = set.horizontal_radix(), m = spec.base_colours;
  const int K = set.window_rows(), L = set.window_cols();
  if (m == 0 || C % m != 0 || C / m < 2)
    throw RequestError("lift",
                       fmt::format("`lift` {}: {} symbols are not a multiple k*{} with k >= 2", spec.text(), C, m));
  WindowLiftProblem p;
  p.spec = spec;
  p.colours = C;
  p.quotient_colours = C / m;
  auto fits = [&](const Tiling& b) {
    return b.kind == TileKind::Window && b.colours == m && b.window_rows == K && b.window_cols == L && b.torus &&
           problem.rows % b.rows == 0 && problem.cols % b.cols == 0 && validate(b).packing;
  };
  if (!spec.base_file.empty()) {
    try {
      p.base = read_tiling_file(spec.base_file);
    } catch (const InputError& e) {
      throw RequestError("lift", fmt::format("`lift` {}: {}", spec.text(), e.what()));
    }
    if (p.base.kind == TileKind::Corner && K == 2 && L == 2) p.base = window_torus_of_corner_torus(p.base);
    p.base_how = spec.base_file;
    if (!fits(p.base))
      throw RequestError("lift", fmt::format("`lift` {}: the base is not a de Bruijn torus with {}x{} windows over {} "
                                             "symbols whose sides divide {}x{}",
                                             spec.text(), K, L, m, problem.rows, problem.cols));
  } else {
    std::vector<Tiling> bases = stored_window_tori(m, K, L);
    if (K == 2 && L == 2)
      if (auto b = construct_window_torus(m, 2, 2, int(m * m), int(m * m))) bases.push_back(b->tiling);
    for (Tiling& b : bases)
      if (fits(b)) {
        p.base = std::move(b);
        p.base_how = fmt::format("stored {}x{} torus", p.base.rows, p.base.cols);
        break;
      }
    if (p.base.cells.empty())
      throw RequestError("lift", fmt::format("`lift` {}: no de Bruijn torus with {}x{} windows over {} symbols whose "
                                             "sides divide {}x{} is known to lift "
                                             "from (give base=FILE)",
                                             spec.text(), K, L, m, problem.rows, problem.cols));
  }
  p.quotient.set = complete_window_set(p.quotient_colours, K, L);
  p.quotient.rows = problem.rows;
  p.quotient.cols = problem.cols;
  p.quotient.torus = p.quotient.packing = true;
  return p;
}

}  // namespace tilekit
