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

namespace {

// The transitions of each state in one direction (forward: leaving it, backward: entering it),
// as compressed rows: state s has rows first[s]..first[s+1] of label ((in, out) of the
// transition) and other (the state at its other end). preds[pfirst[s]..pfirst[s+1]) are the
// states whose rows mention s, the ones whose signature changes when s moves.
struct DirectedTransitions {
  std::vector<std::size_t> first, pfirst;
  std::vector<std::uint64_t> label;
  std::vector<std::uint32_t> other, preds;
};

DirectedTransitions directed_transitions(const Transducer& t, bool forward) {
  const std::size_t n = t.states;
  DirectedTransitions d;
  d.first.assign(n + 1, 0);
  d.pfirst.assign(n + 1, 0);
  d.label.resize(t.transitions.size());
  d.other.resize(t.transitions.size());
  d.preds.resize(t.transitions.size());
  for (const Transition& e : t.transitions)
    ++d.first[(forward ? e.from : e.to) + 1], ++d.pfirst[(forward ? e.to : e.from) + 1];
  std::partial_sum(d.first.begin(), d.first.end(), d.first.begin());
  std::partial_sum(d.pfirst.begin(), d.pfirst.end(), d.pfirst.begin());
  std::vector<std::size_t> fill(d.first.begin(), d.first.end() - 1), pfill(d.pfirst.begin(), d.pfirst.end() - 1);
  for (const Transition& e : t.transitions) {
    const std::size_t k = fill[forward ? e.from : e.to]++;
    d.label[k] = (std::uint64_t(e.in) << 32) | e.out;
    d.other[k] = forward ? e.to : e.from;
    d.preds[pfill[forward ? e.to : e.from]++] = forward ? e.from : e.to;
  }
  return d;
}

// Naive partition refinement with a worklist (Kanellakis & Smolka 1983): a state's signature
// is the set of (in, out, block of the other end) over its transitions; a block whose members
// differ in signature splits, the largest part keeping its id, and the blocks holding a
// predecessor of a moved state are examined again. No block left to split: the partition is
// the coarsest bisimulation.
//
// Blocks are member lists (pos: a state's place in its list). A block is examined only for its
// touched members (predecessors of moved states): the others kept one common signature, so
// one of them (rep) stands for all (Paige & Tarjan's idea; the largest part stays, so a state
// moves O(log n) times).
class BisimulationRefinement {
 public:
  BisimulationRefinement(const DirectedTransitions& d, std::size_t n)
      : d_(d), block_(n, 0), members_(1), pending_(n, 1), current_(n, 0), queued_{1}, queue_{0} {
    members_[0].resize(n);
    std::iota(members_[0].begin(), members_[0].end(), 0u);
    pos_ = members_[0];
    touched_.assign(1, members_[0]);
  }

  // Refines until no block splits; returns state -> block. Checks `budget` every 65,536 states
  // examined.
  std::vector<std::uint32_t> run(const Budget& budget) {
    std::size_t work = 0;
    while (!queue_.empty()) {
      const std::uint32_t b = queue_.back();
      queue_.pop_back();
      queued_[b] = 0;
      const std::size_t size = members_[b].size();
      const std::uint32_t rep = take_touched(b);
      if ((work += list_.size()) >= 65536) work = 0, check_budget(budget);
      compute_signatures();
      const std::vector<Group> groups = group_by_signature(size, rep);
      if (groups.size() > 1) {
        split(b, groups, rep);
      } else {
        for (std::uint32_t s : list_) current_[s] = 0;
      }
    }
    return block_;
  }

  std::size_t blocks() const { return members_.size(); }

 private:
  // The members of a block with one signature among those examined; `has_rep` when rep is among
  // them, and then every untouched member of the block too (counted in size).
  struct Group {
    std::size_t begin, end, size;
    bool has_rep;
  };
  struct Entry {
    std::uint64_t label;
    std::uint32_t other;
    auto operator<=>(const Entry&) const = default;
  };

  // Marks state s's signature as possibly changed: its block is examined again.
  void touch(std::uint32_t s) {
    if (pending_[s]) return;
    pending_[s] = 1;
    touched_[block_[s]].push_back(s);
    if (!queued_[block_[s]]) queued_[block_[s]] = 1, queue_.push_back(block_[s]);
  }

  // The touched members of block b into list_ (marked current), plus one untouched member, rep,
  // when there is one; returns rep (kNoState when every member was touched).
  std::uint32_t take_touched(std::uint32_t b) {
    list_.swap(touched_[b]);
    touched_[b].clear();
    for (std::uint32_t s : list_) pending_[s] = 0, current_[s] = 1;
    std::uint32_t rep = kNoState;
    if (list_.size() < members_[b].size())
      for (std::uint32_t s : members_[b])
        if (!current_[s]) {
          rep = s;
          break;
        }
    if (rep != kNoState) list_.push_back(rep);
    return rep;
  }

  // The sorted, deduplicated signature of each state of list_ (sig_ from sig_first_[i]) and a
  // hash of it.
  void compute_signatures() {
    sig_.clear();
    sig_first_.assign(1, 0);
    hash_.clear();
    for (std::uint32_t s : list_) {
      const std::size_t from = sig_.size();
      for (std::size_t k = d_.first[s]; k < d_.first[s + 1]; ++k) sig_.push_back({d_.label[k], block_[d_.other[k]]});
      std::sort(sig_.begin() + std::ptrdiff_t(from), sig_.end());
      sig_.erase(std::unique(sig_.begin() + std::ptrdiff_t(from), sig_.end()), sig_.end());
      sig_first_.push_back(sig_.size());
      std::uint64_t h = 0;  // an in-memory key only (equal keys are compared in full)
      for (std::size_t k = from; k < sig_.size(); ++k) h = mix_seed(h ^ sig_[k].label) + sig_[k].other;
      hash_.push_back(mix_seed(h));
    }
  }

  // Signature order of list_ entries x and y: by hash, then in full.
  bool less(std::uint32_t x, std::uint32_t y) const {
    if (hash_[x] != hash_[y]) return hash_[x] < hash_[y];
    return std::lexicographical_compare(
        sig_.begin() + std::ptrdiff_t(sig_first_[x]), sig_.begin() + std::ptrdiff_t(sig_first_[x + 1]),
        sig_.begin() + std::ptrdiff_t(sig_first_[y]), sig_.begin() + std::ptrdiff_t(sig_first_[y + 1]));
  }

  // list_ sorted by signature into idx_, and its runs of equal signatures; `size` is the
  // block's member count.
  std::vector<Group> group_by_signature(std::size_t size, std::uint32_t rep) {
    idx_.resize(list_.size());
    std::iota(idx_.begin(), idx_.end(), 0u);
    std::sort(idx_.begin(), idx_.end(), [this](std::uint32_t x, std::uint32_t y) { return less(x, y); });
    std::vector<Group> groups;
    for (std::size_t i = 0, j; i < idx_.size(); i = j) {
      bool r = false;
      for (j = i; j < idx_.size() && (j == i || !less(idx_[i], idx_[j])); ++j) r = r || list_[idx_[j]] == rep;
      // rep's group also holds every untouched member
      groups.push_back({i, j, j - i + (r ? size - (list_.size() - 1) - 1 : 0), r});
    }
    return groups;
  }

  // Block b split by `groups`: every group but the largest becomes a new block, and the
  // predecessors of the states that moved are touched.
  void split(std::uint32_t b, const std::vector<Group>& groups, std::uint32_t rep) {
    std::size_t largest = 0;
    for (std::size_t g = 1; g < groups.size(); ++g)
      if (groups[g].size > groups[largest].size) largest = g;
    moved_.clear();
    for (std::size_t g = 0; g < groups.size(); ++g)
      if (g != largest) move_group(b, groups[g], rep);
    for (std::uint32_t s : list_) current_[s] = 0;
    for (std::uint32_t s : moved_)
      for (std::size_t k = d_.pfirst[s]; k < d_.pfirst[s + 1]; ++k) touch(d_.preds[k]);
  }

  // The members of `group` moved from block b to a new block.
  void move_group(std::uint32_t b, const Group& group, std::uint32_t rep) {
    const std::uint32_t nb = std::uint32_t(members_.size());
    members_.emplace_back();
    touched_.emplace_back();
    queued_.push_back(0);
    std::vector<std::uint32_t> part;
    if (group.has_rep) {  // the untouched members go too
      for (std::uint32_t s : members_[b])
        if (!current_[s]) part.push_back(s);
    }
    for (std::size_t i = group.begin; i < group.end; ++i)
      if (list_[idx_[i]] != rep) part.push_back(list_[idx_[i]]);
    for (std::uint32_t s : part) {
      // swap-remove from b, append to nb
      std::vector<std::uint32_t>& mb = members_[b];
      const std::uint32_t last = mb.back();
      mb[pos_[s]] = last;
      pos_[last] = pos_[s];
      mb.pop_back();
      block_[s] = nb;
      pos_[s] = std::uint32_t(members_[nb].size());
      members_[nb].push_back(s);
      moved_.push_back(s);
    }
  }

  const DirectedTransitions& d_;
  std::vector<std::uint32_t> block_;
  std::vector<std::vector<std::uint32_t>> members_, touched_;
  std::vector<std::uint32_t> pos_;
  std::vector<char> pending_, current_, queued_;
  std::vector<std::uint32_t> queue_;
  // The block being examined: its states (list_), their signatures, and their signature order.
  std::vector<std::uint32_t> list_, idx_, moved_;
  std::vector<Entry> sig_;
  std::vector<std::size_t> sig_first_;
  std::vector<std::uint64_t> hash_;
};

}  // namespace

std::vector<std::uint32_t> merge_bisimilar(Transducer& t, bool forward, const Budget& budget) {
  const std::size_t n = t.states;
  if (n == 0) return {};
  const DirectedTransitions d = directed_transitions(t, forward);
  BisimulationRefinement refinement(d, n);
  std::vector<std::uint32_t> block = refinement.run(budget);
  for (Transition& e : t.transitions) e.from = block[e.from], e.to = block[e.to];
  t.states = std::uint32_t(refinement.blocks());
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
