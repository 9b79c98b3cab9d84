// The torus route of `aperiodic verify` (aperiodic/verify.hpp): periodic tilings as p x q torus
// tilings found by the solver, and bounded n x n squares, within a deadline.
#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <map>
#include <mutex>

#include "aperiodic/rows.hpp"
#include "aperiodic/verify.hpp"
#include "base/error.hpp"
#include "base/parallel.hpp"
#include "base/progress.hpp"
#include "base/signals.hpp"
#include "solver/solve.hpp"
#include "tilesets/validator.hpp"

namespace tilekit {

namespace {

struct Outcome {
  bool found = false, complete = false;
  std::uint64_t nodes = 0;
  SearchStats stats;
  std::optional<Tiling> tiling;
};

using Clock = std::chrono::steady_clock;

// One shape by the solver, within the deadline; a caught signal stops it (with catch_signals).
Outcome search(const TileSet& set, int rows, int cols, bool torus, const Deadline& deadline, bool catch_signals) {
  Outcome out;
  if (deadline.expired() || (catch_signals && SignalCatcher::caught())) return out;  // not searched: incomplete
  TilingProblem p;
  p.set = set;
  p.rows = rows;
  p.cols = cols;
  p.torus = torus;
  p.packing = false;
  SearchOptions o;
  o.mode = SearchMode::First;
  o.run.threads = 1;
  o.run.time_limit = deadline.limited() ? std::max(1e-3, deadline.seconds_left()) : 0;
  o.run.catch_signals = catch_signals;
  o.restarts = 0;  // exhaustive: a failure must be a proof
  SearchResult r = solve(p, o);
  out.nodes = r.nodes;
  out.stats = r.stats;
  out.found = !r.found.empty();
  out.complete = out.found || r.complete;
  if (out.found) out.tiling = r.found.front();
  return out;
}

// The options' bounds: no cap on the sizes (the deadline bounds the work), only on the memory
// the shapes need.
void check_torus_options(const TileSet& set, const VerifyOptions& opts) {
  if (set.empty()) throw InputError(fmt::format("tile set '{}' has no tiles", set.name()));
  if (opts.max_period < 1)
    throw RequestError("max_period", fmt::format("`max_period` must be at least 1, got {}", opts.max_period));
  if (opts.max_square < 0)
    throw RequestError("max_square", fmt::format("`max_square` must be at least 0, got {}", opts.max_square));
  if (std::uint64_t(opts.max_period) * std::uint64_t(opts.max_period) > (std::uint64_t(1) << 26) ||
      std::uint64_t(opts.max_square) * std::uint64_t(opts.max_square) > (std::uint64_t(1) << 28))
    throw RequestError("max_period",
                       fmt::format("`max_period` {} / `max_square` {}: the shapes would not fit in memory",
                                   opts.max_period, opts.max_square));
}

using Shapes = std::vector<std::pair<int, int>>;  // (rows, cols) of torus shapes

// One torus-route run: the set, the deadline and the shared stop token, and the searches of
// one phase (the shapes, their outcomes and the earliest witness).
struct TorusRun {
  const TileSet& set;
  const VerifyOptions& opts;
  Deadline deadline;
  VerifyResult& res;
  StopToken stop;
  std::atomic<std::uint64_t> nodes{0};
  std::mutex stats_mu;  // guards stats: the shapes' engine statistics, summed
  SearchStats stats;
  Shapes shapes;  // the searched shapes of the deciding phase
  std::vector<Outcome> outcomes;
  std::size_t best_index = 0;

  TorusRun(const TileSet& s, const VerifyOptions& o, const Deadline& d, VerifyResult& r)
      : set(s), opts(o), deadline(d), res(r) {}

  bool signals() const { return opts.decide.catch_signals; }
  // The time limit or a caught signal (with the transducer route's catch_signals): stop.
  bool out_of_time() { return poll_stop(stop, deadline, signals()); }

  // Searches `list` in parallel, in order; true when some shape has a witness (the earliest
  // in `list` is shapes[best_index]). Shapes after a known witness are skipped.
  bool search_shapes(const Shapes& list) {
    shapes = list;
    outcomes.assign(list.size(), Outcome{});
    std::atomic<std::size_t> best{list.size()};  // index of the earliest shape with a witness
    std::mutex err_mutex;
    std::string error;
    ProgressReporter progress(fmt::format("verify {}", set.name()), double(list.size()), opts.progress);
    parallel_for(
        std::int64_t(list.size()), res.threads,
        [&](std::int64_t i) {
          const std::size_t k = std::size_t(i);
          if (k > best.load() || out_of_time()) return;  // a smaller witness is known, or time is up
          try {
            outcomes[k] = search(set, list[k].first, list[k].second, true, deadline, signals());
            nodes += outcomes[k].nodes;
            {
              std::lock_guard lock(stats_mu);
              stats += outcomes[k].stats;
            }
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
        },
        &stop);
    progress.finish();
    if (!error.empty()) throw InputError(error);
    best_index = best.load();
    for (std::size_t k = 0; k < list.size() && k <= best_index; ++k) {
      ++res.shapes_searched;
      if (!outcomes[k].complete && k < best_index) ++res.shapes_incomplete;
    }
    if ((stop.reason() == StopReason::TimeLimit || stop.reason() == StopReason::Signal) && best_index == list.size())
      ++res.shapes_incomplete;
    return best_index < list.size();
  }

  // The periodic-row filter (aperiodic/rows.hpp: a horizontal period q needs q-periodic rows
  // that stack forever, a vertical period p the same for columns): the shapes of `large` it
  // cannot rule out, with what it found in `res`.
  Shapes filter(const Shapes& large) {
    const int P = opts.max_period;
    const std::vector<WangTile> as_wang =
        set.kind() == TileKind::Wang ? set.wang_tiles() : corner_to_wang(set).wang_tiles();
    std::vector<PeriodicRows> row_info(std::size_t(P) + 1), col_info(std::size_t(P) + 1);
    auto excluded = [](const PeriodicRows& r) { return r.enumerated && r.recurrent == 0; };
    auto periods = [&](std::vector<PeriodicRows>& info, bool rows) {
      parallel_for(
          P, res.threads,
          [&](std::int64_t i) {  // longest period first
            const int q = P - int(i);
            if (!out_of_time()) info[std::size_t(q)] = periodic_rows(as_wang, q, rows, 2'000'000, deadline, signals());
          },
          &stop);
    };
    if (opts.transducer_filter) periods(row_info, true);
    // Columns matter only when some horizontal period survived.
    bool any_row = false;
    for (int q = 1; q <= P; ++q) any_row = any_row || !excluded(row_info[std::size_t(q)]);
    if (any_row && opts.transducer_filter) periods(col_info, false);
    for (int q = 1; q <= P; ++q) {
      res.periodic_rows.push_back(row_info[std::size_t(q)].enumerated ? row_info[std::size_t(q)].rows : 0);
      res.periodic_cols.push_back(col_info[std::size_t(q)].enumerated ? col_info[std::size_t(q)].rows : 0);
      if (excluded(row_info[std::size_t(q)])) res.excluded_cols.push_back(q);
      if (excluded(col_info[std::size_t(q)])) res.excluded_rows.push_back(q);
    }
    Shapes rest;
    for (auto [p, q] : large) {
      if (excluded(col_info[std::size_t(p)]) || excluded(row_info[std::size_t(q)]))
        ++res.shapes_excluded;
      else
        rest.emplace_back(p, q);
    }
    return rest;
  }

  // The witness of shapes[best_index], checked by the independent validator, into `res`.
  void report_witness() {
    const Outcome& o = outcomes[best_index];
    ValidationReport rep = validate(*o.tiling, &set);
    if (!rep.valid) throw std::runtime_error("solver returned an invalid periodic tiling: " + rep.errors.front());
    res.witness_validated = true;
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

  // The largest n <= max_square with an n x n tiling (downwards from N, so one success settles
  // it); true when a search was cut short.
  bool search_squares() {
    for (int n = opts.max_square; n >= 1; --n) {
      Outcome o = search(set, n, n, false, deadline, signals());
      res.nodes += o.nodes;
      res.stats += o.stats;
      if (o.found) {
        ValidationReport rep = validate(*o.tiling, &set);
        if (!rep.valid) throw std::runtime_error("solver returned an invalid square tiling: " + rep.errors.front());
        res.largest_square = n;
        return false;
      }
      if (!o.complete) return true;
      res.largest_square = n - 1;
    }
    return false;
  }
};

// Torus shapes up to P x P, smallest area first (ties: fewer rows first), so the first witness
// found in this order is one of least area: the small ones (area <= 16) and the rest.
std::pair<Shapes, Shapes> torus_shapes(int P) {
  constexpr int kSmallArea = 16;
  auto by_area = [](auto x, auto y) { return x.first * x.second < y.first * y.second; };
  Shapes small, large;
  for (int p = 1; p <= P; ++p)
    for (int q = 1; q <= P; ++q) (p * q <= kSmallArea ? small : large).emplace_back(p, q);
  std::stable_sort(small.begin(), small.end(), by_area);
  std::stable_sort(large.begin(), large.end(), by_area);
  return {small, large};
}

}  // namespace

VerifyResult torus_route(const TileSet& set, const VerifyOptions& opts, const Deadline& deadline) {
  check_torus_options(set, opts);
  auto t0 = Clock::now();
  VerifyResult res;
  res.threads = resolve_threads(opts.threads);
  TorusRun run(set, opts, deadline, res);

  // Phase A sends the small shapes straight to the solver: periodic sets usually show a small
  // period, and these searches are cheap. Phase B runs the periodic-row filter and sends only
  // the surviving larger shapes to the solver.
  auto [small, large] = torus_shapes(opts.max_period);
  bool found = run.search_shapes(small);
  if (!found && !large.empty()) {
    Shapes rest = run.filter(large);
    if (!run.out_of_time())
      found = run.search_shapes(rest);
    else
      res.shapes_incomplete += rest.size();
  }
  res.nodes = run.nodes.load();
  res.stats = run.stats;
  if (found) run.report_witness();

  bool square_incomplete = false;
  if (opts.max_square > 0 && res.verdict.empty()) {
    square_incomplete = run.search_squares();
    res.square_tileable = res.largest_square == opts.max_square;
  }

  if (res.verdict.empty()) {
    if (opts.max_square > 0 && !square_incomplete && !res.square_tileable)
      res.verdict = "finite";
    else if (res.shapes_incomplete > 0)
      res.verdict = "inconclusive";
    else
      res.verdict = fmt::format("no-period-up-to {}", opts.max_period);
  }
  if (run.signals() && SignalCatcher::caught() && res.verdict != "periodic") {
    res.interrupted = true;  // a signal cut the searches short: nothing is proved beyond the witness
    res.signal = SignalCatcher::caught();
    if (res.verdict == "finite" || res.verdict.rfind("no-period-up-to", 0) == 0) res.verdict = "inconclusive";
  }
  res.route = res.verdict == "periodic" || res.verdict == "finite" ? "torus" : "";
  res.torus_verdict = res.verdict;
  res.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  return res;
}

}  // namespace tilekit
