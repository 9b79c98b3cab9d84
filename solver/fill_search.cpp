#include "solver/fill_search.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <string_view>

#include "base/checkpoint_envelope.hpp"
#include "base/error.hpp"
#include "base/hash.hpp"
#include "base/progress.hpp"
#include "base/random.hpp"
#include "base/run_control.hpp"
#include "base/signals.hpp"
#include "solver/dfs.hpp"
#include "solver/parallel_search.hpp"

namespace tilekit {

FillSearchResult fill_region(const FillRegion& region, const RunSettings& run, std::uint64_t max_dives,
                             const std::string& title) {
  FillSearchResult res;
  FillModel root(region);
  if (!root.consistent()) {  // arc consistency alone refutes it
    res.complete = true;
    return res;
  }
  ParallelConfig cfg;
  cfg.mode = SearchMode::First;
  cfg.run = run;
  cfg.run.checkpoint_path.clear();
  cfg.run.resume_path.clear();
  cfg.title = title;
  cfg.restarts = true;
  // A dive places every cell once: its first limit leaves room for as many backtracks.
  cfg.restart_base = 2 * std::uint64_t(region.rows) * std::uint64_t(region.cols) + 1000;
  cfg.max_dives = max_dives;
  auto leaf = [&](const FillModel& m, SearchCounters& c) {
    ++c.solutions;
    res.tiling = m.tiling();
  };
  ParallelSearch<FillModel> search(root, cfg, leaf);
  const ParallelOutcome out = search.run();
  res.found = out.found;
  res.complete = out.complete;
  res.interrupted = out.interrupted;
  res.timed_out = out.timed_out;
  res.signal = out.signal;
  res.nodes = out.counts.nodes;
  res.restarts = out.restarts;
  res.stats = out.stats;
  return res;
}

namespace {

constexpr std::string_view kMagic = "tilekit-fill-checkpoint";
constexpr int kVersion = 1;
constexpr int kMaxSide = 1 << 15;
constexpr std::int64_t kMaxGrownCells = 512 * 512;  // the largest region a failing block grows to

struct Geometry {
  int rows, cols;
  bool torus;
  // The map cell of window cell (i, j), or -1 outside a bounded map.
  int cell(const FillWindow& w, int i, int j) const {
    int r = w.row + i, c = w.col + j;
    if (torus) {
      r = ((r % rows) + rows) % rows;
      c = ((c % cols) + cols) % cols;
    } else if (r < 0 || r >= rows || c < 0 || c >= cols) {
      return -1;
    }
    return r * cols + c;
  }
};

// The region of `w`: fixed cells as single tiles; with `context`, the cells next to filled map
// cells outside the window restricted to what those allow.
FillRegion make_region(const std::shared_ptr<const FillRules>& rules, const Geometry& g, const FillWindow& w,
                       const std::vector<int>& fixed, const std::vector<int>* context, bool cover = false) {
  FillRegion reg;
  reg.cover = cover;
  reg.rules = rules;
  reg.rows = w.rows;
  reg.cols = w.cols;
  reg.wrap_rows = g.torus && w.rows == g.rows;
  reg.wrap_cols = g.torus && w.cols == g.cols;
  const int words = rules->words();
  reg.domains.assign(std::size_t(w.rows) * std::size_t(w.cols) * std::size_t(words), ~std::uint64_t(0));
  static constexpr int dr[4] = {-1, 0, 1, 0}, dc[4] = {0, 1, 0, -1};
  for (int i = 0; i < w.rows; ++i)
    for (int j = 0; j < w.cols; ++j) {
      std::uint64_t* d = &reg.domains[(std::size_t(i) * std::size_t(w.cols) + std::size_t(j)) * std::size_t(words)];
      const int m = g.cell(w, i, j);
      if (!fixed.empty() && fixed[std::size_t(m)] >= 0) {
        const int t = fixed[std::size_t(m)];
        std::fill(d, d + words, 0);
        d[t >> 6] = std::uint64_t(1) << (t & 63);
      }
      if (!context) continue;
      for (int k = 0; k < 4; ++k) {
        const int ni = i + dr[k], nj = j + dc[k];
        const bool inside_r = reg.wrap_rows || (ni >= 0 && ni < w.rows);
        const bool inside_c = reg.wrap_cols || (nj >= 0 && nj < w.cols);
        if (inside_r && inside_c) continue;
        const int nb = g.cell(w, ni, nj);
        if (nb < 0 || (*context)[std::size_t(nb)] < 0) continue;
        const std::uint64_t* allow = rules->mask((*context)[std::size_t(nb)], fill_opposite(k));
        for (int v = 0; v < words; ++v) d[v] &= allow[v];
      }
    }
  return reg;
}

std::string fingerprint(const FillMapRequest& req, int block, FillOrder order) {
  StableHash h;
  const FillRules& r = *req.rules;
  h.add(std::uint64_t(r.tiles()));
  for (int t = 0; t < r.tiles(); ++t) {
    h.add(std::uint64_t(r.weight(t) * 1e9));
    for (int d = 0; d < kFillDirs; ++d)
      for (int w = 0; w < r.words(); ++w) h.add(r.mask(t, d)[w]);
  }
  h.add(std::uint64_t(req.rows)).add(std::uint64_t(req.cols)).add(req.torus ? 1 : 0).add(std::uint64_t(block));
  h.add(req.dives).add(req.run.seed).add(req.cover ? 1 : 0);
  if (order == FillOrder::Entropy) h.add(0xE);  // Scanline: the fingerprint of checkpoints before the option
  for (int f : req.fixed) h.add(std::uint64_t(std::int64_t(f)), 4);
  return fmt::format("{:016x}", h.mixed());
}

void save_checkpoint(const std::string& path, const std::string& fp, int next, const FillMapOutcome& out) {
  std::string body = fmt::format("fingerprint {}\nnext {} grown {} nodes {} restarts {}\n", fp, next, out.grown,
                                 out.nodes, out.restarts);
  const std::size_t head = body.size();
  body.resize(head + out.map.size() * 4);
  for (std::size_t i = 0; i < out.map.size(); ++i) {
    const auto v = std::uint32_t(out.map[i]);
    for (int b = 0; b < 4; ++b) body[head + i * 4 + std::size_t(b)] = char((v >> (8 * b)) & 0xff);
  }
  write_checkpoint_envelope(path, kMagic, kVersion, body);
}

int load_checkpoint(const std::string& path, const std::string& fp, int blocks, FillMapOutcome& out) {
  const std::string body = read_checkpoint_envelope(path, kMagic, kVersion, kVersion);
  const std::size_t nl1 = body.find('\n');
  const std::size_t nl2 = nl1 == std::string::npos ? nl1 : body.find('\n', nl1 + 1);
  if (nl2 == std::string::npos) throw InputError(fmt::format("checkpoint {}: no header", path));
  if (body.substr(0, nl1) != "fingerprint " + fp)
    throw InputError(fmt::format("checkpoint {} is not this fill's (another set, size, seed or fixed cells)", path));
  int next = 0;
  unsigned long long nodes = 0, restarts = 0;
  if (std::sscanf(body.c_str() + nl1 + 1, "next %d grown %d nodes %llu restarts %llu", &next, &out.grown, &nodes,
                  &restarts) != 4 ||
      next < 0 || next > blocks)
    throw InputError(fmt::format("checkpoint {}: a bad header", path));
  out.nodes = nodes;
  out.restarts = restarts;
  const std::size_t head = nl2 + 1;
  if (body.size() - head != out.map.size() * 4) throw InputError(fmt::format("checkpoint {}: the map's size differs", path));
  for (std::size_t i = 0; i < out.map.size(); ++i) {
    std::uint32_t v = 0;
    for (int b = 0; b < 4; ++b) v |= std::uint32_t(static_cast<unsigned char>(body[head + i * 4 + std::size_t(b)])) << (8 * b);
    out.map[i] = int(v);
  }
  return next;
}

// A window of side s around map cell `m`, inside a bounded map (a torus wraps it).
FillWindow window_around(const Geometry& g, int m, int s_rows, int s_cols) {
  FillWindow w{m / g.cols - (s_rows - 1) / 2, m % g.cols - (s_cols - 1) / 2, s_rows, s_cols};
  if (!g.torus) {
    w.row = std::clamp(w.row, 0, g.rows - s_rows);
    w.col = std::clamp(w.col, 0, g.cols - s_cols);
  } else {
    w.row = ((w.row % g.rows) + g.rows) % g.rows;
    w.col = ((w.col % g.cols) + g.cols) % g.cols;
  }
  return w;
}

// The smallest window found whose fill is refuted, near `near` (fixed cells first), or none.
bool find_proof(const FillMapRequest& req, const Geometry& g, const FillWindow& near, FillWindow& proof) {
  std::vector<int> seeds;
  for (int i = 0; i < near.rows && seeds.size() < 32; ++i)
    for (int j = 0; j < near.cols && seeds.size() < 32; ++j) {
      const int m = g.cell(near, i, j);
      if (m >= 0 && !req.fixed.empty() && req.fixed[std::size_t(m)] >= 0) seeds.push_back(m);
    }
  // windows by area: every placement holding the fixed cell while small, centred beyond
  static constexpr int kShapes[][2] = {{1, 1}, {1, 2}, {2, 1}, {2, 2}, {1, 3}, {3, 1}, {3, 3}, {4, 4}, {5, 5},
                                       {6, 6}, {8, 8}, {10, 10}, {12, 12}, {16, 16}, {24, 24}, {32, 32}};
  for (const auto& shape : kShapes) {
    const int sr = std::min(shape[0], g.rows), sc = std::min(shape[1], g.cols);
    for (int m : seeds) {
      const int span = sr * sc <= 16 ? 1 : 0;  // small windows: every offset
      for (int oi = 0; oi < (span ? sr : 1); ++oi)
        for (int oj = 0; oj < (span ? sc : 1); ++oj) {
          FillWindow w = window_around(g, m, sr, sc);
          if (span) {
            w = window_around(g, m, 1, 1);
            w.rows = sr, w.cols = sc;
            w.row -= oi, w.col -= oj;
            if (g.torus) {
              w.row = (w.row + g.rows) % g.rows, w.col = (w.col + g.cols) % g.cols;
            } else if (w.row < 0 || w.col < 0 || w.row + sr > g.rows || w.col + sc > g.cols) {
              continue;
            }
          }
          if (fill_window_status(req.rules, req.fixed, g.rows, g.cols, g.torus, w, 200000) == 1) {
            proof = w;
            return true;
          }
        }
    }
  }
  if (std::int64_t(g.rows) * g.cols <= 64 * 64) {
    const FillWindow whole{0, 0, g.rows, g.cols};
    if (fill_window_status(req.rules, req.fixed, g.rows, g.cols, g.torus, whole, 2000000) == 1) {
      proof = whole;
      return true;
    }
  }
  return false;
}

}  // namespace

int fill_window_status(const std::shared_ptr<const FillRules>& rules, const std::vector<int>& fixed, int rows,
                       int cols, bool torus, const FillWindow& window, std::uint64_t node_limit) {
  const Geometry g{rows, cols, torus};
  FillModel m(make_region(rules, g, window, fixed, nullptr));
  if (!m.consistent()) return 1;
  struct Control {
    std::uint64_t limit;
    bool found = false;
    bool at_node(const std::vector<Decision>&, const SearchCounters& c) { return !found && c.nodes < limit; }
    void leaf(const FillModel&, SearchCounters&) { found = true; }
  } ctl{node_limit};
  SubtreeSearch<FillModel> dfs;
  SearchCounters counted;
  const SubtreeOutcome o = dfs.run(m, {}, {}, counted, ctl);
  if (ctl.found) return 0;
  return o == SubtreeOutcome::Exhausted ? 1 : -1;
}

FillMapOutcome fill_map(const FillMapRequest& req) {
  if (!req.rules) throw InputError("a fill needs a tile set");
  if (req.rows < 1 || req.cols < 1 || req.rows > kMaxSide || req.cols > kMaxSide)
    throw RequestError("size", fmt::format("map size {}x{} is outside 1..{} per side", req.cols, req.rows, kMaxSide));
  const std::size_t n = std::size_t(req.rows) * std::size_t(req.cols);
  if (!req.fixed.empty() && req.fixed.size() != n) throw InputError("the fixed cells do not match the map's size");
  for (int f : req.fixed)
    if (f < -1 || f >= req.rules->tiles()) throw InputError(fmt::format("fixed tile {} is not in the set", f));
  if (req.block < 0 || req.block > kMaxSide) throw RequestError("block", fmt::format("block side {} out of range", req.block));
  const auto t0 = std::chrono::steady_clock::now();
  const Geometry g{req.rows, req.cols, req.torus};
  int B = req.block;
  if (B == 0) B = std::int64_t(req.rows) * req.cols <= 128 * 128 ? std::max(req.rows, req.cols) : 64;
  const int nbr = (req.rows + B - 1) / B, nbc = (req.cols + B - 1) / B;
  const int blocks = nbr * nbc;
  if (req.cover && blocks > 1)
    throw RequestError("cover", fmt::format("`cover` needs the map in one block (at most {0}x{0} cells, or `block` 0 and a "
                                            "map of at most 128x128)", B));
  // Auto: WFC's order where the map is one search (its frequencies), the scan in blocks (its speed).
  const FillOrder order = req.order != FillOrder::Auto ? req.order : blocks == 1 ? FillOrder::Entropy : FillOrder::Scanline;
  const std::string fp = fingerprint(req, B, order);

  FillMapOutcome out;
  out.map.assign(n, -1);
  std::vector<int> fixed = req.fixed;
  if (req.cover && req.torus && fixed.empty()) {  // translations: tile 0 at (0, 0)
    fixed.assign(n, -1);
    fixed[0] = 0;
  }
  if (!fixed.empty()) out.map = fixed;
  int next = 0;
  if (!req.run.resume_path.empty()) {
    next = load_checkpoint(req.run.resume_path, fp, blocks, out);
    out.resumed = true;
  }
  const Deadline deadline(req.run.time_limit);
  auto last_checkpoint = std::chrono::steady_clock::now();
  auto checkpoint = [&](int at) {
    if (req.run.checkpoint_path.empty()) return;
    save_checkpoint(req.run.checkpoint_path, fp, at, out);
    ++out.checkpoints;
    last_checkpoint = std::chrono::steady_clock::now();
  };
  auto finish = [&] {
    out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return out;
  };
  checkpoint(next);  // the first one before any work: a run killed at once resumes
  ProgressReporter progress("fill", blocks, req.run.progress && blocks > 1);
  progress.set(next);
  for (int b = next; b < blocks; ++b) {
    if (req.run.checkpoint_every > 0 &&
        std::chrono::duration<double>(std::chrono::steady_clock::now() - last_checkpoint).count() >= req.run.checkpoint_every)
      checkpoint(b);
    const FillWindow block{(b / nbc) * B, (b % nbc) * B, std::min(B, req.rows - (b / nbc) * B),
                           std::min(B, req.cols - (b % nbc) * B)};
    // Between blocks too: a block is often filled before its search first polls for a stop.
    const bool signalled = req.run.catch_signals && SignalCatcher::caught() != 0;
    if (signalled || deadline.expired()) {
      out.interrupted = signalled;
      out.timed_out = !signalled;
      out.signal = signalled ? SignalCatcher::caught() : 0;
      out.window = block;
      checkpoint(b);
      return finish();
    }
    int margin = 0;
    for (int attempt = 0;; ++attempt) {
      FillWindow w = block;
      if (margin) {
        w = {block.row - margin, block.col - margin, block.rows + 2 * margin, block.cols + 2 * margin};
        if (w.rows >= req.rows) w.row = 0, w.rows = req.rows;
        if (w.cols >= req.cols) w.col = 0, w.cols = req.cols;
        if (!req.torus) {
          const int r1 = std::min(req.rows, w.row + w.rows), c1 = std::min(req.cols, w.col + w.cols);
          w.row = std::max(0, w.row);
          w.col = std::max(0, w.col);
          w.rows = r1 - w.row;
          w.cols = c1 - w.col;
        }
      }
      const bool whole = w.rows == req.rows && w.cols == req.cols;
      // The cells of the window are searched again: outside it, the map as filled so far.
      std::vector<int> saved(std::size_t(w.rows) * std::size_t(w.cols));
      for (int i = 0; i < w.rows; ++i)
        for (int j = 0; j < w.cols; ++j) {
          const int m = g.cell(w, i, j);
          saved[std::size_t(i) * std::size_t(w.cols) + std::size_t(j)] = out.map[std::size_t(m)];
          out.map[std::size_t(m)] = -1;
        }
      FillRegion reg = make_region(req.rules, g, w, fixed, &out.map, req.cover);
      reg.order = order;
      RunSettings rs = req.run;
      rs.seed = derive_seed(req.run.seed, std::uint64_t(b) * 64 + std::uint64_t(attempt));
      rs.progress = req.run.progress && blocks == 1;
      rs.time_limit = deadline.limited() ? std::max(1e-3, deadline.seconds_left()) : 0;
      // one block that is the whole map restarts until the time limit; any other region gives up
      // after `dives` restarts and grows
      const FillSearchResult r = fill_region(reg, rs, whole && blocks == 1 ? 0 : req.dives);
      out.nodes += r.nodes;
      out.restarts += r.restarts;
      out.stats += r.stats;
      auto restore = [&] {
        for (int i = 0; i < w.rows; ++i)
          for (int j = 0; j < w.cols; ++j)
            out.map[std::size_t(g.cell(w, i, j))] = saved[std::size_t(i) * std::size_t(w.cols) + std::size_t(j)];
      };
      if (r.found) {
        for (int i = 0; i < w.rows; ++i)
          for (int j = 0; j < w.cols; ++j)
            out.map[std::size_t(g.cell(w, i, j))] = int(r.tiling.cells[std::size_t(i) * std::size_t(w.cols) + std::size_t(j)]);
        break;
      }
      restore();
      if (r.interrupted || r.timed_out) {
        out.interrupted = r.interrupted;
        out.timed_out = r.timed_out;
        out.signal = r.signal;
        out.window = block;
        checkpoint(b);
        return finish();
      }
      if (whole || std::int64_t(w.rows + 2 * margin + B) * (w.cols + 2 * margin + B) > kMaxGrownCells) {
        out.window = w;
        out.proved_impossible = find_proof(req, g, w, out.window);
        if (!out.proved_impossible && whole && r.complete) out.proved_impossible = true;
        return finish();
      }
      margin = margin ? margin * 2 : std::max(1, B / 2);
      ++out.grown;
    }
    ++out.blocks;
    progress.add(1);
  }
  progress.finish();
  out.found = true;
  out.window = {0, 0, req.rows, req.cols};
  if (!req.run.checkpoint_path.empty()) checkpoint(blocks);
  return finish();
}

}  // namespace tilekit
