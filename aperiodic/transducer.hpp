#pragma once
// Wang sets as transducers (Jeandel & Rao 2015/2021, "An aperiodic set of 11 Wang tiles",
// sec. 3; Kari 1996, Culik 1996). A tile with colours (n, e, s, w) is a transition from state w
// to state e that reads s and writes n: a row of tiles is a path, its south word the input and
// its north word the output. A strip of k rows is a path of the composition T^k = T o ... o T
// (the output of one row is the input of the next), so
//   - the set tiles the plane iff every T^k has a bi-infinite path (compactness), and
//   - a cycle of T^k whose input word equals its output word is a k-row strip that stacks on
//     itself: a periodic tiling with vertical period k.
// The operations here keep T^k small enough for k to grow (the paper's simplifications):
//   - trim: keep only transitions inside a strongly connected component (Boost.Graph). This
//     keeps every cycle (so every periodic strip) and, by compactness, tileability (see
//     aperiodic/decide.hpp for the argument and the square bound it gives);
//   - merge: quotient by the coarsest forward (or backward) bisimulation: states with the same
//     labelled futures (pasts) become one. The bi-infinite label sequences stay exactly the
//     same (a finite segment of a path lifts by walking forward (backward) from any member of
//     its first (last) class; by Koenig's lemma so does a bi-infinite one).
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "base/parallel.hpp"

namespace tilekit {

inline constexpr std::uint32_t kNoState = std::numeric_limits<std::uint32_t>::max();

struct Transition {
  std::uint32_t from = 0, in = 0, out = 0, to = 0;  // in: the south word, out: the north word
  auto operator<=>(const Transition&) const = default;
};

// A transducer with states 0..states-1 and transitions sorted by (from, in, out, to), no
// duplicates; first[s] .. first[s+1] are the transitions leaving s (after finalize()).
struct Transducer {
  std::uint32_t states = 0;
  std::vector<Transition> transitions;
  std::vector<std::size_t> first;

  bool empty() const { return transitions.empty(); }
  // Sorts, removes duplicates, builds `first`. Every state must be < states.
  void finalize();
  std::size_t bytes() const { return transitions.capacity() * sizeof(Transition) + first.capacity() * sizeof(std::size_t); }
};

// What may stop a long operation: an outside stop (another route answered, a signal seen by the
// caller), a deadline, caught signals, or a memory budget for the transducers being built.
struct Budget {
  const StopToken* stop = nullptr;
  Deadline deadline;
  bool catch_signals = false;  // SignalCatcher::caught() stops the run (StopReason::Signal)
  std::size_t max_bytes = 0;   // 0: no budget
  // The reason to stop now (StopReason::None to go on).
  StopReason check() const;
};

// Thrown by the operations below when the budget says stop; the caller reports how far it got.
struct Stopped {
  StopReason why = StopReason::TimeLimit;
  bool memory = false;  // the memory budget, not the clock
};

// The product of `a` (rows below) and `b` (the row on top): state (p, q) is pair[id] =
// p * b.states + q; (p,q) -x|y-> (p',q') when p -x|c-> p' in a and q -c|y-> q' in b. Only pairs
// that occur in a transition become states. Labels of `b` must be < label_count.
struct Product {
  Transducer t;
  std::vector<std::uint64_t> pair;  // id -> p * b.states + q
};
Product compose(const Transducer& a, const Transducer& b, std::uint32_t label_count, const Budget& budget = {});

// Keeps the transitions whose ends lie in one strongly connected component and the states that
// still have one; returns old state -> new state (kNoState when dropped). `components` gets the
// number of strongly connected components of the states that had a transition.
std::vector<std::uint32_t> trim_to_components(Transducer& t, std::size_t* components = nullptr);

// Quotient by the coarsest forward (backward = false: backward) bisimulation, computed by
// signature refinement; returns old state -> class. Stops (throws Stopped) when asked.
std::vector<std::uint32_t> merge_bisimilar(Transducer& t, bool forward, const Budget& budget = {});

// A cycle using only transitions with in == out (indices into t.transitions, in path order),
// or empty when there is none.
std::vector<std::size_t> find_periodic_cycle(const Transducer& t);

// A cycle whose output word is its input word shifted: out_i == in_{i+shift} (indices mod the
// cycle's length). A k-row strip read that way stacks on itself moved `shift` columns: a tiling
// periodic under the translation (k rows, shift columns), found before k reaches a vertical
// period. Searched in the product with a delay line of |shift| letters, when it has at most
// max_nodes nodes (else nothing is searched and the result is empty). shift 0: as above.
std::vector<std::size_t> find_sheared_cycle(const Transducer& t, int shift, std::uint32_t labels, std::size_t max_nodes);

// A directed graph as out-lists of (target node, edge id).
using Adjacency = std::vector<std::vector<std::pair<std::size_t, std::size_t>>>;
// The edge ids of one cycle in path order, or empty when the graph is acyclic. Iterative, so
// deep graphs are fine.
std::vector<std::size_t> find_cycle(const Adjacency& out);

}  // namespace tilekit
