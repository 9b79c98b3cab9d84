#include "aperiodic/verify.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <map>
#include <mutex>

#include "aperiodic/rows.hpp"
#include "base/error.hpp"
#include "base/parallel.hpp"
#include "base/progress.hpp"
#include "solver/solve.hpp"
#include "tilesets/validator.hpp"

namespace tilekit {

namespace {

struct Outcome {
  bool found = false, complete = false;
  std::uint64_t nodes = 0;
  std::optional<Tiling> tiling;
};

// opts.time_limit bounds the whole verification, not each search: a search gets what is left
// of it (issue 15: a limit of 20 s used to run for 66-93 s). Past the deadline a search is not
// started and counts as incomplete.
struct Deadline {
  std::chrono::steady_clock::time_point start;
  double limit = 0;  // seconds; 0: none
  // Seconds a search may run: 0 for no limit, negative once the deadline has passed.
  double left() const {
    if (limit <= 0) return 0;
    const double used = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return used < limit ? std::max(limit - used, 1e-3) : -1;
  }
};

Outcome search(const TileSet& set, int rows, int cols, bool torus, const Deadline& deadline) {
  const double time_limit = deadline.left();
  if (time_limit < 0) return {};  // not searched: incomplete
  TilingProblem p;
  p.set = set;
  p.rows = rows;
  p.cols = cols;
  p.torus = torus;
  p.packing = false;
  SearchOptions o;
  o.mode = SearchMode::First;
  o.threads = 1;
  o.time_limit = time_limit;
  o.restarts = 0;  // exhaustive: a failure must be a proof
  SearchResult r = solve(p, o);
  Outcome out;
  out.nodes = r.nodes;
  out.found = !r.found.empty();
  out.complete = out.found || r.complete;
  if (out.found) out.tiling = r.found.front();
  return out;
}

}  // namespace

VerifyResult verify_tile_set(const TileSet& set, const VerifyOptions& opts) {
  if (set.empty()) throw InputError(fmt::format("tile set '{}' has no tiles", set.name()));
  if (opts.max_period < 1 || opts.max_period > 64)
    throw InputError(fmt::format("--max-period must be between 1 and 64, got {}", opts.max_period));
  if (opts.max_square < 0 || opts.max_square > 256)
    throw InputError(fmt::format("--max-square must be between 0 and 256, got {}", opts.max_square));
  if (!(opts.time_limit >= 0) || !std::isfinite(opts.time_limit))
    throw InputError(fmt::format("--time-limit must be a number of seconds >= 0, got {}", opts.time_limit));
  auto t0 = std::chrono::steady_clock::now();
  const Deadline deadline{t0, opts.time_limit};
  VerifyResult res;
  res.threads = opts.threads > 0 ? opts.threads : default_thread_count();

  // Torus shapes, smallest area first (ties: fewer rows first), so the first witness found
  // in this order is one of least area. Phase A sends the small shapes (area <= 16) straight
  // to the solver: periodic sets usually show a small period, and these searches are cheap.
  // Phase B runs the row/column transducer filter (aperiodic/rows.hpp: a
  // horizontal period q needs q-periodic rows that stack forever, a vertical period p the
  // same for columns) and sends only the surviving larger shapes to the solver.
  const int P = opts.max_period;
  constexpr int kSmallArea = 16;
  auto by_area = [](auto x, auto y) { return x.first * x.second < y.first * y.second; };
  std::vector<std::pair<int, int>> small, large;
  for (int p = 1; p <= P; ++p)
    for (int q = 1; q <= P; ++q) (p * q <= kSmallArea ? small : large).emplace_back(p, q);
  std::stable_sort(small.begin(), small.end(), by_area);
  std::stable_sort(large.begin(), large.end(), by_area);

  std::atomic<std::uint64_t> nodes{0};
  std::vector<std::pair<int, int>> shapes;  // the searched shapes of the deciding phase
  std::vector<Outcome> outcomes;
  std::size_t best_index = 0;
  auto search_shapes = [&](const std::vector<std::pair<int, int>>& list) {
    shapes = list;
    outcomes.assign(list.size(), Outcome{});
    std::atomic<std::size_t> best{list.size()};  // index of the earliest shape with a witness
    std::mutex err_mutex;
    std::string error;
    ProgressReporter progress(fmt::format("verify {}", set.name()), double(list.size()), opts.progress);
    parallel_for(std::int64_t(list.size()), res.threads, [&](std::int64_t i) {
      const std::size_t k = std::size_t(i);
      if (k > best.load()) return;  // a smaller witness is already known
      try {
        outcomes[k] = search(set, list[k].first, list[k].second, true, deadline);
        nodes += outcomes[k].nodes;
        if (outcomes[k].found) {
          std::size_t cur = best.load();
          while (k < cur && !best.compare_exchange_weak(cur, k)) {
          }
        }
      } catch (const std::exception& e) {
        std::lock_guard<std::mutex> lock(err_mutex);
        error = e.what();
      }
      progress.add(1);
    });
    progress.finish();
    if (!error.empty()) throw InputError(error);
    best_index = best.load();
    for (std::size_t k = 0; k < list.size() && k <= best_index; ++k) {
      ++res.shapes_searched;
      if (!outcomes[k].complete && k < best_index) ++res.shapes_incomplete;
    }
    return best_index < list.size();
  };

  bool found = search_shapes(small);
  if (!found && !large.empty()) {
    const std::vector<WangTile> as_wang =
        set.kind() == TileKind::Wang ? set.wang_tiles() : corner_to_wang(set).wang_tiles();
    std::vector<PeriodicRows> row_info(std::size_t(P) + 1), col_info(std::size_t(P) + 1);
    auto excluded = [](const PeriodicRows& r) { return r.enumerated && r.recurrent == 0; };
    if (opts.transducer_filter) {
      parallel_for(P, res.threads, [&](std::int64_t i) {  // longest period first
        const int q = P - int(i);
        row_info[std::size_t(q)] = periodic_rows(as_wang, q, true);
      });
    }
    // Columns matter only when some horizontal period survived.
    bool any_row = false;
    for (int q = 1; q <= P; ++q) any_row = any_row || !excluded(row_info[std::size_t(q)]);
    if (any_row && opts.transducer_filter) {
      parallel_for(P, res.threads, [&](std::int64_t i) {
        const int p = P - int(i);
        col_info[std::size_t(p)] = periodic_rows(as_wang, p, false);
      });
    }
    for (int q = 1; q <= P; ++q) {
      res.periodic_rows.push_back(row_info[std::size_t(q)].enumerated ? row_info[std::size_t(q)].rows : 0);
      res.periodic_cols.push_back(col_info[std::size_t(q)].enumerated ? col_info[std::size_t(q)].rows : 0);
      if (excluded(row_info[std::size_t(q)])) res.excluded_cols.push_back(q);
      if (excluded(col_info[std::size_t(q)])) res.excluded_rows.push_back(q);
    }
    std::vector<std::pair<int, int>> rest;
    for (auto [p, q] : large) {
      if (excluded(col_info[std::size_t(p)]) || excluded(row_info[std::size_t(q)]))
        ++res.shapes_excluded;
      else
        rest.emplace_back(p, q);
    }
    found = search_shapes(rest);
  }
  res.nodes = nodes.load();

  if (found) {
    const Outcome& o = outcomes[best_index];
    // Independent check of the witness before it is reported.
    ValidationReport rep = validate(*o.tiling, &set);
    if (!rep.valid) throw std::runtime_error("solver returned an invalid periodic tiling: " + rep.errors.front());
    res.verdict = "periodic";
    res.period = shapes[best_index];
    res.witness_tiling = o.tiling;
    std::map<TileIndex, std::int64_t> number;
    for (std::size_t k = 0; k < set.size(); ++k) number[set.index_of(k)] = std::int64_t(k);
    for (int r = 0; r < o.tiling->rows; ++r) {
      std::vector<std::int64_t> row;
      for (int c = 0; c < o.tiling->cols; ++c) row.push_back(number.at(o.tiling->at(r, c)));
      res.witness.push_back(row);
    }
  }

  // Square search: the largest n <= max_square with an n x n tiling (downwards from N, so
  // one success settles it).
  bool square_incomplete = false;
  if (opts.max_square > 0 && res.verdict.empty()) {
    for (int n = opts.max_square; n >= 1; --n) {
      Outcome o = search(set, n, n, false, deadline);
      res.nodes += o.nodes;
      if (o.found) {
        ValidationReport rep = validate(*o.tiling, &set);
        if (!rep.valid) throw std::runtime_error("solver returned an invalid square tiling: " + rep.errors.front());
        res.largest_square = n;
        break;
      }
      if (!o.complete) {
        square_incomplete = true;
        break;
      }
      res.largest_square = n - 1;
    }
    res.square_tileable = res.largest_square == opts.max_square;
  }

  if (res.verdict.empty()) {
    if (opts.max_square > 0 && !square_incomplete && !res.square_tileable)
      res.verdict = "cannot-tile";
    else if (res.shapes_incomplete > 0)
      res.verdict = "inconclusive";
    else
      res.verdict = fmt::format("no-period-up-to {}", opts.max_period);
  }
  res.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return res;
}

}  // namespace tilekit
