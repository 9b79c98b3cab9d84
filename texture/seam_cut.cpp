#include "texture/seam_cut.hpp"

#include <cassert>
#include <cmath>
#include <cstdlib>
#include <limits>

namespace tilekit {

CutPath min_error_cut(const CutBand& b) {
  assert(b.rows > 0 && b.width > 0 && int(b.lo.size()) == b.rows && int(b.hi.size()) == b.rows);
  assert(b.cost.size() == std::size_t(b.rows) * std::size_t(b.width));
  assert(b.rise.empty() || b.rise.size() == b.cost.size());
  assert(b.fall.empty() || b.fall.size() == b.cost.size());
  constexpr double inf = std::numeric_limits<double>::infinity();
  const std::size_t w = std::size_t(b.width);
  std::vector<double> acc(std::size_t(b.rows) * w, inf);  // cumulative error E(r, p), Efros & Freeman eq.
  std::vector<int> from(acc.size(), -1);
  const int mid = (b.width - 1) / 2;
  auto better = [&](int p, int q) {  // tie-break: nearer the middle, then lower
    const int dp = std::abs(p - mid), dq = std::abs(q - mid);
    return dp != dq ? dp < dq : p < q;
  };
  for (int p = b.lo[0]; p <= b.hi[0]; ++p) acc[std::size_t(p)] = b.cost[std::size_t(p)];
  for (int r = 1; r < b.rows; ++r)
    for (int p = b.lo[r]; p <= b.hi[r]; ++p) {
      double best = inf;
      int arg = -1;
      for (int d = -1; d <= 1; ++d) {
        if (b.diagonal && d == 0) continue;
        const int q = p + d;
        if (q < 0 || q >= b.width) continue;
        const std::size_t here = std::size_t(r) * w + std::size_t(p);
        const double v = acc[std::size_t(r - 1) * w + std::size_t(q)] +
                         (d < 0 && !b.rise.empty()   ? b.rise[here]
                          : d > 0 && !b.fall.empty() ? b.fall[here]
                                                     : 0.0);
        if (v < best || (v == best && v < inf && arg >= 0 && better(q, arg))) best = v, arg = q;
      }
      if (arg < 0 || best == inf) continue;
      acc[std::size_t(r) * w + std::size_t(p)] = best + b.cost[std::size_t(r) * w + std::size_t(p)];
      from[std::size_t(r) * w + std::size_t(p)] = arg;
    }
  CutPath path;
  path.pos.assign(std::size_t(b.rows), -1);
  const std::size_t last = std::size_t(b.rows - 1) * w;
  int end = -1;
  for (int p = b.lo[b.rows - 1]; p <= b.hi[b.rows - 1]; ++p)
    if (acc[last + std::size_t(p)] < inf &&
        (end < 0 || acc[last + std::size_t(p)] < acc[last + std::size_t(end)] ||
         (acc[last + std::size_t(p)] == acc[last + std::size_t(end)] && better(p, end))))
      end = p;
  assert(end >= 0 && "the cut band admits no path");
  path.cost = acc[last + std::size_t(end)];
  for (int r = b.rows - 1, p = end; r >= 0; --r) {
    path.pos[std::size_t(r)] = p;
    p = from[std::size_t(r) * w + std::size_t(p)];
  }
  return path;
}

}  // namespace tilekit
