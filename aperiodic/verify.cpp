#include "aperiodic/verify.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <stdexcept>

#include "base/error.hpp"
#include "base/run_control.hpp"
#include "base/signals.hpp"

namespace tilekit {

namespace {

using Clock = std::chrono::steady_clock;

void take_decision(VerifyResult& res, const DecideResult& d) {
  res.verdict = d.verdict;
  res.route = d.verdict == "unknown" ? "" : "transducer";
  if (d.verdict == "periodic") {
    res.period = {d.period_rows, d.period_cols};
    res.witness = d.witness;
    res.witness_tiling = d.witness_tiling;
    res.witness_validated = d.witness_validated;
  }
  res.interrupted = d.interrupted;
}

// The two routes must agree where both decided (each is checked on its own; this checks them
// against each other): a periodic set is not finite, and a torus search that covered the
// transducer's least periods must have found a witness.
void cross_check(const DecideResult& d, const VerifyResult& t, int max_period) {
  const bool torus_periodic = t.torus_verdict == "periodic";
  if ((d.verdict == "finite" && torus_periodic) || (d.verdict == "periodic" && t.torus_verdict == "finite"))
    throw std::logic_error(fmt::format("verify: the transducer route says {}, the torus route {}", d.verdict, t.torus_verdict));
  if (d.verdict == "periodic" && t.torus_verdict.rfind("no-period-up-to", 0) == 0 && d.period_rows <= max_period &&
      d.period_cols <= max_period)
    throw std::logic_error(fmt::format("verify: the transducer route found a {}x{} period that the torus route missed",
                                       d.period_rows, d.period_cols));
}

}  // namespace

VerifyResult verify_tile_set(const TileSet& set, const VerifyOptions& opts) {
  if (set.empty()) throw InputError(fmt::format("tile set '{}' has no tiles", set.name()));
  if (opts.route != "auto" && opts.route != "transducer" && opts.route != "torus" && opts.route != "both")
    throw RequestError("route", fmt::format("`route` must be auto, transducer, torus or both, got '{}'", opts.route));
  if (!(opts.time_limit >= 0) || !std::isfinite(opts.time_limit))
    throw RequestError("time_limit",
                       fmt::format("`time_limit` must be a number of seconds >= 0, got {}", opts.time_limit));
  const auto t0 = Clock::now();
  const Deadline deadline(opts.time_limit, t0);
  // One signal stops every route: the catcher spans the whole run, and a route it interrupted
  // starts no other.
  std::optional<SignalCatcher> signals;
  if (opts.decide.catch_signals) signals.emplace();
  VerifyResult res;
  std::optional<DecideResult> decision;
  if (opts.route != "torus") {
    DecideOptions d = opts.decide;
    // "both" leaves the torus route half of the time at least.
    d.time_limit = opts.route == "both" && deadline.limited() ? opts.time_limit / 2
                   : deadline.limited()                       ? opts.time_limit
                                                              : 0;
    d.progress = opts.progress;
    decision = decide_tile_set(set, d);
    take_decision(res, *decision);
    if (res.interrupted) res.signal = decision->signal;
  }
  const bool run_torus =
      !res.interrupted && (opts.route == "torus" || opts.route == "both" ||
                           (opts.route == "auto" && res.verdict == "unknown" && !deadline.expired()));
  if (run_torus) {
    VerifyResult t = torus_route(set, opts, deadline);
    if (decision) cross_check(*decision, t, opts.max_period);
    if (!decision || res.route.empty()) {
      t.transducer = decision;
      res = std::move(t);
    } else {
      res.torus_verdict = t.torus_verdict;
      res.nodes = t.nodes;
      res.stats = t.stats;
      res.shapes_searched = t.shapes_searched;
      res.shapes_incomplete = t.shapes_incomplete;
      res.shapes_excluded = t.shapes_excluded;
      res.largest_square = t.largest_square;
      res.threads = t.threads;
      res.interrupted = t.interrupted;
      res.signal = t.signal;
    }
  }
  if (decision && !res.transducer) res.transducer = decision;
  // Neither route decided: the transducer's "unknown" (with its k) unless the torus route ran
  // on its own terms.
  if (res.route.empty() && decision && !run_torus) res.verdict = "unknown";
  res.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  return res;
}

}  // namespace tilekit
