#include "aperiodic/transducer.hpp"

#include <boost/graph/compressed_sparse_row_graph.hpp>
#include <boost/graph/strong_components.hpp>
#include <boost/property_map/property_map.hpp>

#include <algorithm>
#include <cassert>
#include <numeric>
#include <unordered_map>

#include "base/random.hpp"
#include "base/signals.hpp"

namespace tilekit {

StopReason Budget::check() const {
  if (stop && stop->requested()) return stop->reason() == StopReason::Signal ? StopReason::Signal : StopReason::Found;
  if (catch_signals && SignalCatcher::caught()) return StopReason::Signal;
  if (deadline.expired()) return StopReason::TimeLimit;
  return StopReason::None;
}

namespace {

void check_budget(const Budget& b) {
  if (StopReason why = b.check(); why != StopReason::None) throw Stopped{why, false};
}

void check_memory(const Budget& b, std::size_t bytes) {
  if (b.max_bytes > 0 && bytes > b.max_bytes) throw Stopped{StopReason::Error, true};
}

// Dense ids for pairs (p, q): a flat table when it is small, a hash map otherwise.
class PairIds {
 public:
  PairIds(std::uint64_t a, std::uint64_t b) : b_(b) {
    if (a * b <= (std::uint64_t(1) << 24)) flat_.assign(std::size_t(a * b), kNoState);
  }
  std::uint32_t id(std::uint32_t p, std::uint32_t q, std::vector<std::uint64_t>& pairs) {
    const std::uint64_t key = std::uint64_t(p) * b_ + q;
    std::uint32_t* slot;
    if (!flat_.empty()) slot = &flat_[std::size_t(key)];
    else slot = &map_.try_emplace(key, kNoState).first->second;
    if (*slot == kNoState) {
      if (pairs.size() >= kNoState) throw Stopped{StopReason::Error, true};  // more than 2^32 - 1 states
      *slot = std::uint32_t(pairs.size());
      pairs.push_back(key);
    }
    return *slot;
  }

 private:
  std::uint64_t b_;
  std::vector<std::uint32_t> flat_;
  std::unordered_map<std::uint64_t, std::uint32_t> map_;
};

}  // namespace

void Transducer::finalize() {
  std::sort(transitions.begin(), transitions.end());
  transitions.erase(std::unique(transitions.begin(), transitions.end()), transitions.end());
  first.assign(std::size_t(states) + 1, 0);
  for (const Transition& t : transitions) {
    assert(t.from < states && t.to < states);
    ++first[std::size_t(t.from) + 1];
  }
  std::partial_sum(first.begin(), first.end(), first.begin());
}

Product compose(const Transducer& a, const Transducer& b, std::uint32_t label_count, const Budget& budget) {
  assert(a.first.size() == std::size_t(a.states) + 1 && b.first.size() == std::size_t(b.states) + 1);
  // b's transitions by input label (counting sort).
  std::vector<std::size_t> start(std::size_t(label_count) + 1, 0);
  for (const Transition& t : b.transitions) {
    assert(t.in < label_count);
    ++start[std::size_t(t.in) + 1];
  }
  std::partial_sum(start.begin(), start.end(), start.begin());
  std::vector<std::size_t> by_in(b.transitions.size()), fill(start.begin(), start.end() - 1);
  for (std::size_t i = 0; i < b.transitions.size(); ++i) by_in[fill[b.transitions[i].in]++] = i;

  Product out;
  PairIds ids(a.states, b.states);
  std::size_t since_check = 0;
  for (std::uint32_t p = 0; p < a.states; ++p) {
    for (std::size_t ai = a.first[p]; ai < a.first[std::size_t(p) + 1]; ++ai) {
      const Transition& ta = a.transitions[ai];
      if (ta.out >= label_count) continue;  // no row above can read it
      for (std::size_t k = start[ta.out]; k < start[std::size_t(ta.out) + 1]; ++k) {
        const Transition& tb = b.transitions[by_in[k]];
        const std::uint32_t from = ids.id(p, tb.from, out.pair), to = ids.id(ta.to, tb.to, out.pair);
        out.t.transitions.push_back({from, ta.in, tb.out, to});
      }
      if ((since_check += start[std::size_t(ta.out) + 1] - start[ta.out] + 1) >= 4096) {
        since_check = 0;
        check_budget(budget);
        // The sort in finalize() may need the list twice over.
        check_memory(budget, 2 * out.t.transitions.capacity() * sizeof(Transition) + out.pair.capacity() * 12);
      }
    }
  }
  out.t.states = std::uint32_t(out.pair.size());
  out.t.finalize();
  return out;
}

std::vector<std::uint32_t> trim_to_components(Transducer& t, std::size_t* components) {
  using Graph = boost::compressed_sparse_row_graph<boost::directedS>;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
  edges.reserve(t.transitions.size());
  for (const Transition& e : t.transitions) edges.emplace_back(e.from, e.to);  // sorted by from
  Graph g(boost::edges_are_sorted, edges.begin(), edges.end(), std::size_t(t.states));
  std::vector<std::size_t> comp(t.states, 0);
  std::size_t n = t.states == 0 ? 0
                                 : boost::strong_components(g, boost::make_iterator_property_map(
                                                                   comp.begin(), boost::get(boost::vertex_index, g)));
  if (components) *components = n;
  std::vector<std::uint32_t> renum(t.states, kNoState);
  std::vector<Transition> kept;
  for (const Transition& e : t.transitions)
    if (comp[e.from] == comp[e.to]) kept.push_back(e);
  std::uint32_t next = 0;
  for (const Transition& e : kept) {
    if (renum[e.from] == kNoState) renum[e.from] = next++;
    if (renum[e.to] == kNoState) renum[e.to] = next++;
  }
  for (Transition& e : kept) e.from = renum[e.from], e.to = renum[e.to];
  t.states = next;
  t.transitions = std::move(kept);
  t.finalize();
  return renum;
}

std::vector<std::uint32_t> merge_bisimilar(Transducer& t, bool forward, const Budget& budget) {
  // Naive partition refinement with a worklist (Kanellakis & Smolka 1983): a state's signature
  // is the set of (in, out, block of the other end) over its transitions; a block whose members
  // differ in signature splits, the largest part keeping its id, and the blocks holding a
  // predecessor of a moved state are examined again. No block left to split: the partition is
  // the coarsest bisimulation.
  const std::size_t n = t.states;
  std::vector<std::uint32_t> block(n, 0);
  if (n == 0) return block;
  // Transitions of each state in the chosen direction (forward: leaving it, backward: entering),
  // and its predecessors in that direction (the states whose signature mentions it).
  std::vector<std::size_t> first(n + 1, 0), pfirst(n + 1, 0);
  std::vector<std::uint64_t> label(t.transitions.size());  // (in, out) of each transition, by state
  std::vector<std::uint32_t> other(t.transitions.size()), preds(t.transitions.size());
  for (const Transition& e : t.transitions) ++first[(forward ? e.from : e.to) + 1], ++pfirst[(forward ? e.to : e.from) + 1];
  std::partial_sum(first.begin(), first.end(), first.begin());
  std::partial_sum(pfirst.begin(), pfirst.end(), pfirst.begin());
  {
    std::vector<std::size_t> fill(first.begin(), first.end() - 1), pfill(pfirst.begin(), pfirst.end() - 1);
    for (const Transition& e : t.transitions) {
      const std::size_t k = fill[forward ? e.from : e.to]++;
      label[k] = (std::uint64_t(e.in) << 32) | e.out;
      other[k] = forward ? e.to : e.from;
      preds[pfill[forward ? e.to : e.from]++] = forward ? e.from : e.to;
    }
  }
  struct Entry {
    std::uint64_t label;
    std::uint32_t other;
    auto operator<=>(const Entry&) const = default;
  };
  // Blocks as member lists (pos: a state's place in its list). A block is examined only for its
  // touched members (predecessors of moved states): the others kept one common signature, so
  // one of them (rep) stands for all (Paige & Tarjan's idea; the largest part stays, so a state
  // moves O(log n) times).
  std::vector<std::vector<std::uint32_t>> members(1);
  members[0].resize(n);
  std::iota(members[0].begin(), members[0].end(), 0u);
  std::vector<std::uint32_t> pos(members[0]);
  std::vector<std::vector<std::uint32_t>> touched(1, members[0]);
  std::vector<char> pending(n, 1), current(n, 0), queued{1};
  std::vector<std::uint32_t> queue{0};
  auto touch = [&](std::uint32_t s) {
    if (pending[s]) return;
    pending[s] = 1;
    touched[block[s]].push_back(s);
    if (!queued[block[s]]) queued[block[s]] = 1, queue.push_back(block[s]);
  };
  std::vector<Entry> sig;
  std::vector<std::size_t> sig_first;
  std::vector<std::uint64_t> hash;
  std::vector<std::uint32_t> list, idx, moved;
  std::size_t work = 0;
  while (!queue.empty()) {
    const std::uint32_t b = queue.back();
    queue.pop_back();
    queued[b] = 0;
    list.swap(touched[b]);
    touched[b].clear();
    for (std::uint32_t s : list) pending[s] = 0, current[s] = 1;
    const std::size_t size = members[b].size();
    std::uint32_t rep = kNoState;  // an untouched member, standing for all of them
    if (list.size() < size)
      for (std::uint32_t s : members[b])
        if (!current[s]) {
          rep = s;
          break;
        }
    if (rep != kNoState) list.push_back(rep);
    if ((work += list.size()) >= 65536) work = 0, check_budget(budget);
    sig.clear();
    sig_first.assign(1, 0);
    hash.clear();
    for (std::uint32_t s : list) {
      const std::size_t from = sig.size();
      for (std::size_t k = first[s]; k < first[s + 1]; ++k) sig.push_back({label[k], block[other[k]]});
      std::sort(sig.begin() + std::ptrdiff_t(from), sig.end());
      sig.erase(std::unique(sig.begin() + std::ptrdiff_t(from), sig.end()), sig.end());
      sig_first.push_back(sig.size());
      std::uint64_t h = 0;  // an in-memory key only (equal keys are compared in full)
      for (std::size_t k = from; k < sig.size(); ++k) h = mix_seed(h ^ sig[k].label) + sig[k].other;
      hash.push_back(mix_seed(h));
    }
    auto less = [&](std::uint32_t x, std::uint32_t y) {
      if (hash[x] != hash[y]) return hash[x] < hash[y];
      return std::lexicographical_compare(sig.begin() + std::ptrdiff_t(sig_first[x]), sig.begin() + std::ptrdiff_t(sig_first[x + 1]),
                                          sig.begin() + std::ptrdiff_t(sig_first[y]), sig.begin() + std::ptrdiff_t(sig_first[y + 1]));
    };
    idx.resize(list.size());
    std::iota(idx.begin(), idx.end(), 0u);
    std::sort(idx.begin(), idx.end(), less);
    struct Group {
      std::size_t begin, end, size;
      bool has_rep;
    };
    std::vector<Group> groups;
    for (std::size_t i = 0, j; i < idx.size(); i = j) {
      bool r = false;
      for (j = i; j < idx.size() && (j == i || !less(idx[i], idx[j])); ++j) r = r || list[idx[j]] == rep;
      // rep's group also holds every untouched member
      groups.push_back({i, j, j - i + (r ? size - (list.size() - 1) - 1 : 0), r});
    }
    if (groups.size() > 1) {
      std::size_t largest = 0;
      for (std::size_t g = 1; g < groups.size(); ++g)
        if (groups[g].size > groups[largest].size) largest = g;
      moved.clear();
      for (std::size_t g = 0; g < groups.size(); ++g) {
        if (g == largest) continue;
        const std::uint32_t nb = std::uint32_t(members.size());
        members.emplace_back();
        touched.emplace_back();
        queued.push_back(0);
        std::vector<std::uint32_t> part;
        if (groups[g].has_rep) {  // the untouched members go too
          for (std::uint32_t s : members[b])
            if (!current[s]) part.push_back(s);
        }
        for (std::size_t i = groups[g].begin; i < groups[g].end; ++i)
          if (list[idx[i]] != rep) part.push_back(list[idx[i]]);
        for (std::uint32_t s : part) {
          // swap-remove from b, append to nb
          std::vector<std::uint32_t>& mb = members[b];
          const std::uint32_t last = mb.back();
          mb[pos[s]] = last;
          pos[last] = pos[s];
          mb.pop_back();
          block[s] = nb;
          pos[s] = std::uint32_t(members[nb].size());
          members[nb].push_back(s);
          moved.push_back(s);
        }
      }
      for (std::uint32_t s : list) current[s] = 0;
      for (std::uint32_t s : moved)
        for (std::size_t k = pfirst[s]; k < pfirst[s + 1]; ++k) touch(preds[k]);
    } else {
      for (std::uint32_t s : list) current[s] = 0;
    }
  }
  for (Transition& e : t.transitions) e.from = block[e.from], e.to = block[e.to];
  t.states = std::uint32_t(members.size());
  t.finalize();
  return block;
}

std::vector<std::size_t> find_cycle(const Adjacency& out) {
  // Iterative depth-first search; a back edge closes the cycle.
  enum : std::uint8_t { White, OnStack, Done };
  const std::size_t n = out.size();
  std::vector<std::uint8_t> colour(n, White);
  struct Frame {
    std::size_t node, next, via;  // via: the edge that entered node
  };
  std::vector<Frame> stack;
  std::vector<std::size_t> pos(n, 0);  // position of a node on the stack
  for (std::size_t root = 0; root < n; ++root) {
    if (colour[root] != White) continue;
    stack.push_back({root, 0, 0});
    colour[root] = OnStack;
    pos[root] = 0;
    while (!stack.empty()) {
      Frame& f = stack.back();
      if (f.next == out[f.node].size()) {
        colour[f.node] = Done;
        stack.pop_back();
        continue;
      }
      auto [v, id] = out[f.node][f.next++];
      if (colour[v] == OnStack) {
        std::vector<std::size_t> cycle;
        for (std::size_t i = pos[v] + 1; i < stack.size(); ++i) cycle.push_back(stack[i].via);
        cycle.push_back(id);
        return cycle;
      }
      if (colour[v] == White) {
        colour[v] = OnStack;
        pos[v] = stack.size();
        stack.push_back({v, 0, id});
      }
    }
  }
  return {};
}

std::vector<std::size_t> find_periodic_cycle(const Transducer& t) {
  Adjacency out(t.states);
  for (std::size_t i = 0; i < t.transitions.size(); ++i)
    if (t.transitions[i].in == t.transitions[i].out) out[t.transitions[i].from].emplace_back(t.transitions[i].to, i);
  std::vector<std::size_t> cycle = find_cycle(out);
  for (std::size_t i = 0; i < cycle.size(); ++i) {
    [[maybe_unused]] const Transition& e = t.transitions[cycle[i]];
    assert(e.in == e.out && e.to == t.transitions[cycle[(i + 1) % cycle.size()]].from);
  }
  return cycle;
}

std::vector<std::size_t> find_sheared_cycle(const Transducer& t, int shift, std::uint32_t labels, std::size_t max_nodes) {
  if (shift == 0) return find_periodic_cycle(t);
  // Node (state, the last |shift| outputs (shift > 0) or inputs (shift < 0), oldest first, as a
  // number in base `labels`); a transition may follow when its input (output) is the oldest of
  // them, which it replaces by its output (input) at the newest end.
  const std::size_t d = std::size_t(shift > 0 ? shift : -shift);
  std::uint64_t span = 1;
  for (std::size_t i = 0; i < d; ++i)
    if (__builtin_mul_overflow(span, std::uint64_t(labels), &span)) return {};
  if (span == 0 || std::uint64_t(t.states) * span > max_nodes) return {};
  const std::uint64_t older = span / labels;  // weight of the oldest letter
  Adjacency out(std::size_t(t.states * span));
  for (std::size_t i = 0; i < t.transitions.size(); ++i) {
    const Transition& e = t.transitions[i];
    const std::uint32_t must = shift > 0 ? e.in : e.out, push = shift > 0 ? e.out : e.in;
    if (must >= labels || push >= labels) continue;
    for (std::uint64_t rest = 0; rest < older; ++rest) {
      const std::uint64_t code = must * older + rest, next = rest * labels + push;
      out[std::size_t(e.from * span + code)].emplace_back(std::size_t(e.to * span + next), i);
    }
  }
  std::vector<std::size_t> cycle = find_cycle(out);
  for (std::size_t i = 0; i < cycle.size(); ++i) {  // out_i == in_{i+shift}, cyclically
    [[maybe_unused]] const std::size_t m = cycle.size(), j = (i + m + std::size_t(shift % std::ptrdiff_t(m) + std::ptrdiff_t(m))) % m;
    assert(t.transitions[cycle[i]].out == t.transitions[cycle[j]].in);
  }
  return cycle;
}

}  // namespace tilekit
