#include "aperiodic/chain.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cassert>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <unordered_map>

#include "base/error.hpp"
#include "base/resources.hpp"

namespace tilekit {

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Transitions of `t` leaving `from` that read `in`: a range of t.transitions.
std::pair<std::size_t, std::size_t> reading(const Transducer& t, std::uint32_t from, std::uint32_t in) {
  auto b = t.transitions.begin() + std::ptrdiff_t(t.first[from]), e = t.transitions.begin() + std::ptrdiff_t(t.first[from + 1]);
  auto lo = std::lower_bound(b, e, Transition{from, in, 0, 0});
  auto hi = std::lower_bound(lo, e, Transition{from, in + 1, 0, 0});
  return {std::size_t(lo - t.transitions.begin()), std::size_t(hi - t.transitions.begin())};
}

}  // namespace

TransducerChain::TransducerChain(const std::vector<WangTile>& tiles, bool columns, bool merge, const Budget& budget)
    : columns_(columns), merge_(merge) {
  // Columns are the rows of the transposed set (n <-> w, s <-> e).
  for (const WangTile& t : tiles) tiles_.push_back(columns ? WangTile{t.w, t.s, t.e, t.n} : t);
  // States: the E/W colours, labels: the N/S colours, both numbered densely in increasing order.
  std::vector<Colour> state, label;
  for (const WangTile& t : tiles_) state.push_back(t.w), state.push_back(t.e), label.push_back(t.n), label.push_back(t.s);
  for (auto* v : {&state, &label}) {
    std::sort(v->begin(), v->end());
    v->erase(std::unique(v->begin(), v->end()), v->end());
  }
  auto id = [](const std::vector<Colour>& v, Colour c) {
    return std::uint32_t(std::lower_bound(v.begin(), v.end(), c) - v.begin());
  };
  labels_ = std::uint32_t(label.size());
  base_.states = std::uint32_t(state.size());
  std::vector<Transition> of_tile;
  for (const WangTile& t : tiles_) of_tile.push_back({id(state, t.w), id(label, t.s), id(label, t.n), id(state, t.e)});
  base_.transitions = of_tile;
  base_.finalize();
  assert(base_.transitions.size() == tiles_.size() && "tiles must be distinct");

  auto t0 = std::chrono::steady_clock::now();
  ChainLevel one;
  one.t = base_;
  one.product_states = base_.states;
  one.product_transitions = base_.transitions.size();
  if (StopReason why = budget.check(); why != StopReason::None) throw Stopped{why, false};
  std::vector<std::uint32_t> renum = trim_to_components(one.t, &one.components);
  if (StopReason why = budget.check(); why != StopReason::None) throw Stopped{why, false};
  // The tile of each transition T_1 kept: both lists sorted, then walked together.
  for (std::uint32_t k = 0; k < of_tile.size(); ++k) {
    Transition tr = of_tile[k];
    if (renum[tr.from] == kNoState || renum[tr.to] == kNoState) continue;
    tr.from = renum[tr.from], tr.to = renum[tr.to];
    tile_of_.emplace_back(tr, k);
  }
  std::sort(tile_of_.begin(), tile_of_.end());
  std::size_t kept = 0;
  for (std::size_t i = 0, j = 0; i < tile_of_.size(); ++i) {
    while (j < one.t.transitions.size() && one.t.transitions[j] < tile_of_[i].first) ++j;
    if (j < one.t.transitions.size() && one.t.transitions[j] == tile_of_[i].first) tile_of_[kept++] = tile_of_[i];
  }
  tile_of_.resize(kept);
  assert(tile_of_.size() == one.t.transitions.size());
  one.seconds = seconds_since(t0);
  levels_.push_back(std::move(one));
}

void TransducerChain::extend(const Budget& budget) {
  assert(!levels_.empty());
  auto t0 = std::chrono::steady_clock::now();
  ChainLevel next;
  Product p = compose(levels_.back().t, levels_.front().t, labels_, budget);
  next.product_states = p.t.states;
  next.product_transitions = p.t.transitions.size();
  std::vector<std::uint32_t> cls = trim_to_components(p.t, &next.components);
  // Merge forward, backward, forward, ... until a direction finds nothing to merge after the
  // other one did: then the partition is stable both ways.
  for (int calls = 0; merge_; ++calls) {
    const std::uint32_t before = p.t.states;
    std::vector<std::uint32_t> q = merge_bisimilar(p.t, calls % 2 == 0, budget);
    for (std::uint32_t& c : cls)
      if (c != kNoState) c = q[c];
    if (calls > 0 && p.t.states == before) break;
  }
  std::vector<std::pair<std::uint64_t, std::uint32_t>> kept;
  for (std::size_t id = 0; id < cls.size(); ++id)
    if (cls[id] != kNoState) kept.emplace_back(p.pair[id], cls[id]);
  std::sort(kept.begin(), kept.end());
  for (auto& [key, c] : kept) {
    assert(c < p.t.states);
    next.keys.push_back(key);
    next.cls.push_back(c);
  }
  next.t = std::move(p.t);
  next.seconds = seconds_since(t0);
  levels_.push_back(std::move(next));
}

TransducerChain::Strip TransducerChain::periodic_strip(const Budget& budget, int max_shift) const {
  const Transducer& t = levels_.back().t;
  const std::size_t max_nodes = 4 * t.transitions.size() + 4096;
  for (int a = 0; a <= max_shift; ++a)
    for (int shift : {a, -a}) {
      if (a == 0 && shift < 0) continue;
      std::vector<std::size_t> cycle = find_sheared_cycle(t, shift, labels_, max_nodes);
      if (cycle.empty()) continue;
      std::vector<Step> steps;
      for (std::size_t i : cycle)
        steps.push_back({t.transitions[i].from, t.transitions[i].in, t.transitions[i].out, t.transitions[i].to});
      return {lift(k(), steps, budget), shift};
    }
  return {};
}

std::vector<std::vector<std::uint32_t>> TransducerChain::lift(int j, const std::vector<Step>& cycle,
                                                                const Budget& budget) const {
  assert(!cycle.empty());
  for (std::size_t i = 0; i < cycle.size(); ++i) assert(cycle[i].to == cycle[(i + 1) % cycle.size()].from);
  if (j == 1) {
    std::vector<std::uint32_t> row;
    for (const Step& s : cycle) {
      Transition tr{s.from, s.in, s.out, s.to};
      auto it = std::lower_bound(tile_of_.begin(), tile_of_.end(), std::make_pair(tr, std::uint32_t(0)));
      if (it == tile_of_.end() || it->first != tr) throw std::logic_error("transducer lift: a T_1 transition has no tile");
      row.push_back(it->second);
    }
    return {row};
  }
  // The lift graph: nodes (phase i, product state (p, q) of class cycle[i].from), edges the product
  // transitions that read cycle[i].in and write cycle[i].out into a member of the next phase.
  // Bisimulation quotients keep bi-infinite paths, so this finite graph has a cycle.
  const ChainLevel& level = levels_[std::size_t(j) - 1];
  const Transducer& below = levels_[std::size_t(j) - 2].t;
  const Transducer& top = levels_.front().t;
  const std::uint64_t nb = top.states;
  const std::size_t m = cycle.size();
  std::unordered_map<std::uint32_t, std::vector<std::size_t>> phases;
  for (std::size_t i = 0; i < m; ++i) phases[cycle[i].from].push_back(i);
  std::vector<std::vector<std::uint64_t>> members(m);
  for (std::size_t i = 0; i < level.keys.size(); ++i)
    if (auto it = phases.find(level.cls[i]); it != phases.end())
      for (std::size_t ph : it->second) members[ph].push_back(level.keys[i]);  // sorted, as keys are
  std::vector<std::size_t> offset(m + 1, 0);
  for (std::size_t i = 0; i < m; ++i) offset[i + 1] = offset[i] + members[i].size();
  Adjacency adj(offset[m]);
  struct Edge {
    std::size_t src, dst;
    std::uint32_t c;
  };
  std::vector<Edge> edges;
  for (std::size_t i = 0; i < m; ++i) {
    if (budget.check() != StopReason::None) throw Stopped{budget.check(), false};
    const std::size_t ni = (i + 1) % m;
    for (std::size_t pos = 0; pos < members[i].size(); ++pos) {
      const std::uint32_t p = std::uint32_t(members[i][pos] / nb), q = std::uint32_t(members[i][pos] % nb);
      auto [alo, ahi] = reading(below, p, cycle[i].in);
      for (std::size_t ai = alo; ai < ahi; ++ai) {
        const Transition& ta = below.transitions[ai];
        auto [blo, bhi] = reading(top, q, ta.out);
        for (std::size_t bi = blo; bi < bhi; ++bi) {
          const Transition& tb = top.transitions[bi];
          if (tb.out != cycle[i].out) continue;
          const std::uint64_t key = std::uint64_t(ta.to) * nb + tb.to;
          auto it = std::lower_bound(members[ni].begin(), members[ni].end(), key);
          if (it == members[ni].end() || *it != key) continue;
          const std::size_t dst = offset[ni] + std::size_t(it - members[ni].begin());
          adj[offset[i] + pos].emplace_back(dst, edges.size());
          edges.push_back({offset[i] + pos, dst, ta.out});
        }
      }
    }
  }
  std::vector<std::size_t> found = find_cycle(adj);
  if (found.empty()) throw std::logic_error(fmt::format("transducer lift: no cycle over a periodic cycle of T_{}", j));
  auto phase = [&](std::size_t node) { return std::size_t(std::upper_bound(offset.begin(), offset.end(), node) - offset.begin()) - 1; };
  auto start = std::find_if(found.begin(), found.end(), [&](std::size_t e) { return phase(edges[e].src) == 0; });
  assert(start != found.end() && found.size() % m == 0);
  std::rotate(found.begin(), start, found.end());
  std::vector<Step> lower, upper;
  for (std::size_t e : found) {
    const Edge& ed = edges[e];
    const std::size_t i = phase(ed.src), ni = phase(ed.dst);
    const std::uint64_t a = members[i][ed.src - offset[i]], b = members[ni][ed.dst - offset[ni]];
    lower.push_back({std::uint32_t(a / nb), cycle[i].in, ed.c, std::uint32_t(b / nb)});
    upper.push_back({std::uint32_t(a % nb), ed.c, cycle[i].out, std::uint32_t(b % nb)});
  }
  std::vector<std::vector<std::uint32_t>> rows = lift(j - 1, lower, budget);
  std::vector<std::uint32_t> row = lift(1, upper, budget).front();
  const std::size_t width = rows.front().size();
  assert(width % row.size() == 0);
  std::vector<std::uint32_t> repeated;
  repeated.reserve(width);
  while (repeated.size() < width) repeated.insert(repeated.end(), row.begin(), row.end());
  rows.push_back(std::move(repeated));
  return rows;
}

SquareBound TransducerChain::square_bound() const {
  // n <= (k(c_1-1)+1) * c_2 * ... * c_k - 1 (header), and any square below k rows is allowed.
  SquareBound b;
  const std::uint64_t k = levels_.size();
  std::uint64_t value = k * (levels_.front().components - 1) + 1;
  bool overflow = false;
  b.log10 = std::log10(double(value));
  for (std::size_t j = 1; j < levels_.size(); ++j) {
    overflow = overflow || __builtin_mul_overflow(value, levels_[j].components, &value);
    b.log10 += std::log10(double(std::max<std::uint64_t>(levels_[j].components, 1)));
  }
  if (!overflow) b.side = std::max(value - 1, k - 1);
  return b;
}

std::size_t TransducerChain::bytes() const {
  std::size_t n = base_.bytes();
  for (const ChainLevel& l : levels_) n += l.t.bytes() + l.keys.capacity() * 8 + l.cls.capacity() * 4;
  return n;
}

void TransducerChain::check_level(ChainLevel& l, int k) const {
  auto bad = [&](const char* why) { return InputError(fmt::format("level {} of the transducer chain: {}", k, why)); };
  for (std::size_t i = 0; i < l.t.transitions.size(); ++i) {
    const Transition& e = l.t.transitions[i];
    if (e.from >= l.t.states || e.to >= l.t.states || e.in >= labels_ || e.out >= labels_) throw bad("transition out of range");
    if (i > 0 && !(l.t.transitions[i - 1] < e)) throw bad("transitions not sorted");
  }
  // Every state of a stored level lies on a cycle (trim_to_components), so it has a transition
  // of its own: a count of states beyond the transitions (which the file's size bounds) is damage,
  // and would size the index below by the damaged count.
  if (l.t.states > l.t.transitions.size()) throw bad("more states than transitions");
  require_memory(double(l.t.states) * 8.0, fmt::format("level {} of the transducer chain ({} states)", k, l.t.states));
  l.t.finalize();  // the index of transitions by state
  if (k == 1) return;
  const std::uint64_t range = std::uint64_t(levels_[std::size_t(k) - 2].t.states) * levels_.front().t.states;
  if (l.keys.size() != l.cls.size()) throw bad("product states and classes differ in number");
  for (std::size_t i = 0; i < l.keys.size(); ++i) {
    if (l.keys[i] >= range || l.cls[i] >= l.t.states) throw bad("product state out of range");
    if (i > 0 && l.keys[i - 1] >= l.keys[i]) throw bad("product states not sorted");
  }
}

bool TransducerChain::rederives(const Budget& budget) const {
  TransducerChain fresh(tiles_, false, merge_, budget);  // tiles_ are oriented already
  for (int k = 1; k < this->k(); ++k) fresh.extend(budget);
  for (std::size_t i = 0; i < levels_.size(); ++i) {
    const ChainLevel &a = levels_[i], &b = fresh.levels_[i];
    if (a.t.states != b.t.states || a.t.transitions != b.t.transitions || a.keys != b.keys || a.cls != b.cls ||
        a.components != b.components || a.product_states != b.product_states ||
        a.product_transitions != b.product_transitions)
      return false;
  }
  return true;
}

TransducerChain TransducerChain::restore(const std::vector<WangTile>& tiles, bool columns, bool merge,
                                         std::vector<ChainLevel> levels) {
  TransducerChain c(tiles, columns, merge, Budget{});
  if (levels.empty() || levels.front().t.transitions != c.levels_.front().t.transitions ||
      levels.front().components != c.levels_.front().components)
    throw InputError("the transducer chain does not belong to this tile set");
  for (std::size_t k = 1; k < levels.size(); ++k) {
    c.levels_.push_back(std::move(levels[k]));
    c.check_level(c.levels_.back(), int(k) + 1);
  }
  return c;
}

}  // namespace tilekit
