#include "aperiodic/decide.hpp"

#include <fmt/format.h>

#include <cassert>
#include <chrono>
#include <cmath>
#include <memory>
#include <new>
#include <numeric>
#include <stdexcept>

#include "aperiodic/convert.hpp"
#include "aperiodic/decide_checkpoint.hpp"
#include "base/error.hpp"
#include "base/progress.hpp"
#include "base/resources.hpp"
#include "base/signals.hpp"
#include "checkpoints/checkpoint.hpp"
#include "tilesets/validator.hpp"

namespace tilekit {

namespace {

using Clock = std::chrono::steady_clock;

DecideLevel level_stats(const TransducerChain& c) {
  const ChainLevel& l = c.level(c.k());
  return {c.k(), c.columns() ? "columns" : "rows", l.product_states, l.product_transitions, l.components,
          l.t.states, l.t.transitions.size(), l.seconds};
}

std::string stop_name(const Stopped& s) {
  if (s.memory) return "memory";
  switch (s.why) {
    case StopReason::Signal: return "signal";
    case StopReason::TimeLimit: return "time-limit";
    default: return "stopped";
  }
}

// A k-row strip (bottom row first, in the chain's orientation) whose top word is its bottom
// word moved `shift` letters, stacked into a torus of the set's own orientation, top row first:
// each strip above is the one below moved `shift` columns, R = W / gcd(W, shift) of them close up.
std::vector<std::vector<std::int64_t>> strip_torus(const TransducerChain::Strip& strip, bool columns) {
  const std::size_t k = strip.rows.size(), w = strip.rows.front().size();
  const std::size_t s = std::size_t((strip.shift % std::ptrdiff_t(w) + std::ptrdiff_t(w)) % std::ptrdiff_t(w));
  const std::size_t blocks = w / std::gcd(w, s == 0 ? w : s);
  const std::size_t rows = k * blocks;
  std::vector<std::vector<std::int64_t>> g(rows, std::vector<std::int64_t>(w));
  for (std::size_t j = 0; j < blocks; ++j)    // block j from the bottom: the strip moved j * shift
    for (std::size_t r = 0; r < k; ++r)       // row r of the strip from the bottom
      for (std::size_t c = 0; c < w; ++c) g[rows - 1 - (j * k + r)][c] = strip.rows[r][(c + j * s) % w];
  if (!columns) return g;
  // The chain saw the transposed set: tile (r, c) of the set is tile (c, r) there.
  std::vector<std::vector<std::int64_t>> t(w, std::vector<std::int64_t>(rows));
  for (std::size_t r = 0; r < rows; ++r)
    for (std::size_t c = 0; c < w; ++c) t[c][r] = g[r][c];
  return t;
}

bool indices_fit(const TileSet& set) { return std::uint64_t(set.horizontal_radix()) * set.vertical_radix() <= 65535; }

// The independent check of a periodic witness before it is reported: the validator on tile
// indices (thesis eq. 2.2/2.5), with colours relabelled densely when the set's own radix makes
// indices overflow 32 bits. Past that (over 65535 colour pairs) only a direct edge check is
// possible, and the result says so.
void check_witness(const TileSet& set, DecideResult& res) {
  const TileSet& own = set;
  std::optional<TileSet> relabelled;
  if (!indices_fit(own)) relabelled = relabel_colours(set);
  const TileSet& vset = relabelled ? *relabelled : own;
  if (indices_fit(vset)) {
    res.witness_tiling = numbers_to_tiling(vset, res.witness);
    ValidationReport rep = validate(*res.witness_tiling, &vset);
    if (!rep.valid) throw std::logic_error("transducer method produced an invalid periodic tiling: " + rep.errors.front());
    res.witness_validated = true;
    return;
  }
  const std::vector<WangTile> w = decision_tiles(set);
  const std::size_t rows = res.witness.size(), cols = res.witness.front().size();
  for (std::size_t r = 0; r < rows; ++r)
    for (std::size_t c = 0; c < cols; ++c) {
      const WangTile& t = w[std::size_t(res.witness[r][c])];
      if (t.e != w[std::size_t(res.witness[r][(c + 1) % cols])].w || t.s != w[std::size_t(res.witness[(r + 1) % rows][c])].n)
        throw std::logic_error("transducer method produced an invalid periodic tiling");
    }
  res.witness_validated = false;
}

}  // namespace

std::vector<WangTile> decision_tiles(const TileSet& set) {
  // thesis 2.9: the equivalent Wang set has the same tilings, tile for tile.
  return set.kind() == TileKind::Wang ? set.wang_tiles() : corner_to_wang(set).wang_tiles();
}

std::vector<std::vector<std::int64_t>> least_period(const std::vector<std::vector<std::int64_t>>& g) {
  const std::size_t rows = g.size(), cols = g.front().size();
  auto periodic = [&](std::size_t p, std::size_t q) {
    for (std::size_t r = 0; r < rows; ++r)
      for (std::size_t c = 0; c < cols; ++c)
        if (g[r][c] != g[(r + p) % rows][(c + q) % cols]) return false;
    return true;
  };
  std::size_t p = 1, q = 1;
  while (rows % p != 0 || !periodic(p, 0)) ++p;
  while (cols % q != 0 || !periodic(0, q)) ++q;
  std::vector<std::vector<std::int64_t>> out(p);
  for (std::size_t r = 0; r < p; ++r) out[r].assign(g[r].begin(), g[r].begin() + std::ptrdiff_t(q));
  return out;
}

Tiling numbers_to_tiling(const TileSet& set, const std::vector<std::vector<std::int64_t>>& grid) {
  // Tile indices are 32-bit (thesis eq. 2.2/2.5): (ch * cv)^2 must fit.
  const std::uint32_t ch = set.horizontal_radix(), cv = set.vertical_radix();
  if (!indices_fit(set))
    throw InputError(fmt::format("tile set '{}': {} x {} colours make tile indices overflow 32 bits", set.name(), ch, cv));
  Tiling t(set.kind(), ch, int(grid.size()), int(grid.front().size()), true);
  if (set.kind() == TileKind::Wang) t.vertical_colours = cv;
  for (int r = 0; r < t.rows; ++r)
    for (int c = 0; c < t.cols; ++c) t.at(r, c) = set.index_of(std::size_t(grid[std::size_t(r)][std::size_t(c)]));
  return t;
}

namespace {

// A level just built: finite or periodic? Records the verdict in `res` (true: decided).
bool record_verdict(DecideResult& res, const TransducerChain& c, Budget& budget, const DecideOptions& o) {
  if (c.finite()) {
    res.verdict = "finite";
    SquareBound b = c.square_bound();
    res.square_bound = b.side;
    res.square_bound_log10 = b.log10;
  } else {
    TransducerChain::Strip strip;
    try {
      strip = c.periodic_strip(budget);
    } catch (const std::logic_error& e) {
      // Every cycle of a chain this build made lifts; one read from a checkpoint may not.
      if (!res.resumed) throw;
      throw InputError(fmt::format("checkpoint {}: its transducer chain is not the one the tile set gives ({}); "
                                   "delete it to start afresh",
                                   o.resume_path, e.what()));
    }
    if (strip.rows.empty()) return false;
    res.shift = strip.shift;
    res.witness = least_period(strip_torus(strip, c.columns()));
    res.period_rows = int(res.witness.size());
    res.period_cols = int(res.witness.front().size());
    res.verdict = "periodic";
  }
  res.direction = c.columns() ? "columns" : "rows";
  res.k = c.k();
  return true;
}

}  // namespace

DecideResult decide_tile_set(const TileSet& set, const DecideOptions& o) {
  if (set.empty()) throw InputError(fmt::format("tile set '{}' has no tiles", set.name()));
  if (!o.rows && !o.columns) throw InputError("decide: at least one of rows and columns is needed");
  if (!(o.time_limit >= 0) || !std::isfinite(o.time_limit))
    throw RequestError("time_limit",
                       fmt::format("`time_limit` must be a number of seconds >= 0, got {}", o.time_limit));
  if (o.max_k < 0) throw RequestError("max_k", fmt::format("`max_k` must be >= 0, got {}", o.max_k));
  const auto t0 = Clock::now();
  std::optional<SignalCatcher> signals;
  if (o.catch_signals) signals.emplace();
  const std::vector<WangTile> tiles = decision_tiles(set);
  const std::string fingerprint = decide_fingerprint(tiles, o);
  DecideResult res;
  DecideCheckpoint state;
  state.fingerprint = fingerprint;
  if (!o.resume_path.empty()) {
    state = read_decide_checkpoint(o.resume_path, tiles);
    if (std::string diff = fingerprint_difference(fingerprint, state.fingerprint); !diff.empty())
      throw InputError(fmt::format("checkpoint {} does not match this run: {}", o.resume_path, diff));
    res.resumed = true;
    res.levels = state.levels;
  }
  const double before = state.seconds;
  auto elapsed = [&] { return std::chrono::duration<double>(Clock::now() - t0).count(); };
  Budget budget;
  budget.stop = o.stop;
  budget.catch_signals = o.catch_signals;
  budget.deadline = Deadline(o.time_limit, t0);
  const std::size_t memory = o.memory_limit > 0 ? o.memory_limit : memory_limit();
  ProgressReporter progress(fmt::format("decide {}", set.name()), o.time_limit, o.progress);
  auto last_checkpoint = Clock::now();
  auto save = [&] {
    if (o.checkpoint_path.empty() || state.chains.empty()) return;
    state.seconds = before + elapsed();
    state.levels = res.levels;
    write_decide_checkpoint(o.checkpoint_path, state);
    ++res.checkpoints;
    last_checkpoint = Clock::now();
  };
  auto decided = [&](const TransducerChain& c) { return record_verdict(res, c, budget, o); };
  try {
    bool done = false;
    if (!res.resumed)
      for (bool columns : {false, true}) {
        if (columns ? !o.columns : !o.rows) continue;
        if (StopReason why = budget.check(); why != StopReason::None) throw Stopped{why, false};
        state.chains.emplace_back(tiles, columns, o.merge, budget);
        res.levels.push_back(level_stats(state.chains.back()));
      }
    for (const TransducerChain& c : state.chains)
      if (!done) done = decided(c);
    while (!done) {
      // The cheaper chain grows next (its last product as the measure); ties: rows.
      TransducerChain* next = nullptr;
      for (TransducerChain& c : state.chains) {
        if (o.max_k > 0 && c.k() >= o.max_k) continue;
        if (!next || c.level(c.k()).product_transitions < next->level(next->k()).product_transitions) next = &c;
      }
      if (!next) {
        res.stopped_by = "max-k";
        break;
      }
      std::size_t used = 0;
      for (const TransducerChain& c : state.chains) used += c.bytes();
      if (used >= memory) throw Stopped{StopReason::Error, true};
      budget.max_bytes = memory - used;
      next->extend(budget);
      res.levels.push_back(level_stats(*next));
      done = decided(*next);
      std::string detail;
      for (const TransducerChain& c : state.chains)
        detail += fmt::format("{}{} k={} ({} states, {} transitions)", detail.empty() ? "" : ", ",
                              c.columns() ? "columns" : "rows", c.k(), c.level(c.k()).t.states,
                              c.level(c.k()).t.transitions.size());
      progress.update(o.time_limit > 0 ? elapsed() : 0, o.time_limit, detail);
      if (!done && o.checkpoint_every > 0 &&
          std::chrono::duration<double>(Clock::now() - last_checkpoint).count() >= o.checkpoint_every)
        save();
    }
    // A finite verdict rests on T_k being empty: from a checkpoint, the chain must re-derive
    // from the tiles before the verdict is given (a damaged or edited level could empty it).
    if (res.resumed && res.verdict == "finite")
      for (const TransducerChain& c : state.chains)
        if (c.finite() && !c.rederives(budget))
          throw InputError(fmt::format("checkpoint {}: its transducer chain is not the one the tile set gives "
                                       "(it does not re-derive); delete it to start afresh",
                                       o.resume_path));
  } catch (const Stopped& s) {
    res.stopped_by = stop_name(s);
    if (res.verdict == "finite") res.verdict = "unknown";  // stopped while re-deriving: not confirmed
  } catch (const std::bad_alloc&) {
    res.stopped_by = "memory";
    if (res.verdict == "finite") res.verdict = "unknown";
  }
  progress.finish();
  for (const TransducerChain& c : state.chains) {
    (c.columns() ? res.k_columns : res.k_rows) = c.k();
    if (res.verdict == "unknown") res.k = std::max(res.k, c.k());
  }
  if (res.stopped_by == "signal") {
    res.interrupted = true;
    res.signal = SignalCatcher::caught();
  }
  if (res.verdict == "unknown") save();  // where a later run resumes (also after a signal)
  if (res.verdict == "periodic") check_witness(set, res);
  res.seconds = elapsed();
  res.total_seconds = before + res.seconds;
  return res;
}

}  // namespace tilekit
