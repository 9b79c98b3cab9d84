#pragma once
// Knuth's estimate of the size of a backtrack tree (D. E. Knuth, "Estimating the efficiency
// of backtrack programs", Math. Comp. 29, 1975): follow one random root-to-leaf path; with
// d_i the number of children of the i-th node on it, 1 + d_1 + d_1 d_2 + ... is an unbiased
// estimate of the number of nodes. Averaging many probes reduces the variance.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "base/random.hpp"
#include "solver/model.hpp"

namespace tilekit {

struct TreeEstimate {
  double nodes = 0;        // mean over the probes (infinite beyond double's range)
  double log10_nodes = 0;  // the same as a logarithm: finite for trees of any size
  double leaves = 0;  // estimated number of leaves (solutions)
  std::uint64_t probes = 0;
};

// `stop()` is asked before every probe (the time limit, a signal): the estimate then rests on the
// probes made so far (est.probes), so no probe count runs without bound.
template <SearchModel M, class Stop = bool (*)()>
TreeEstimate knuth_estimate(
    const M& root, std::uint64_t probes, std::uint64_t seed, Stop stop = [] { return false; }) {
  SplitMix64 rng(mix_seed(seed ^ 0x6b6e757468ull));
  TreeEstimate est;
  std::vector<int> values, ok;
  // log(a + b) from log a and log b
  auto log_add = [](double a, double b) { return std::max(a, b) + std::log1p(std::exp(-std::abs(a - b))); };
  double log_sum = -INFINITY;  // log of the sum of the probes' totals
  std::uint64_t made = 0;
  for (; made < probes && !stop(); ++made) {
    M m = root;
    double weight = 1, total = 1, log_weight = 0, log_total = 0;
    for (;;) {
      int var = m.branch(values);
      if (var < 0) {
        est.leaves += weight;
        break;
      }
      ok.clear();
      for (int v : values) {
        if (m.assign(var, v)) ok.push_back(v);
        m.unassign(var, v);
      }
      if (ok.empty()) break;
      weight *= double(ok.size());
      total += weight;
      log_weight += std::log(double(ok.size()));
      log_total = log_add(log_total, log_weight);
      int v = ok[rng.below(ok.size())];
      m.assign(var, v);
    }
    est.nodes += total;
    log_sum = log_add(log_sum, log_total);
  }
  if (made) {
    est.nodes /= double(made);
    est.leaves /= double(made);
    est.log10_nodes = (log_sum - std::log(double(made))) / std::log(10.0);
  }
  est.probes = made;
  return est;
}

}  // namespace tilekit
