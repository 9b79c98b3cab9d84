// The problem helpers of problem.hpp: the complete packing problem and the size check.
#include "solver/problem.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "base/error.hpp"
#include "solver/model.hpp"

namespace tilekit {

TilingProblem complete_packing_problem(TileKind kind, std::int64_t colours) {
  if (colours < 1 || colours > std::int64_t(kMaxPackingColours))
    throw InputError(fmt::format("--colors must be between 1 and {} for a packing of the complete set, got {}",
                                 kMaxPackingColours, colours));
  TilingProblem p;
  const auto c = std::uint32_t(colours);
  p.set = kind == TileKind::Wang ? complete_wang_set(c, c) : complete_corner_set(c);
  p.rows = p.cols = int(c * c);
  p.torus = true;
  p.packing = true;
  return p;
}

void check_searchable(const TilingProblem& p) {
  const TileSet& set = p.set;
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
