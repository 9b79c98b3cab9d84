#pragma once
// The transducers T_1, T_2, ... of one Wang set (Jeandel & Rao 2015, sec. 3; see
// aperiodic/transducer.hpp): T_1 is the set's transducer trimmed to its strongly connected
// components, T_k = merge(trim(T_{k-1} o T_1)). Each level remembers which product states became
// which of its states, so that a periodic cycle found in T_k can be lifted back to an actual
// k-row strip of tiles (the witness), and how many strongly connected components each product
// had (the square bound of a finite proof).
//
// The square bound. Let T_k be empty and take a k x n rectangle, n >= k. Each of its k rows is
// a path in T, which crosses between components at most c_1 - 1 times; cutting there leaves a
// run of at least (n - k(c_1-1)) / (k(c_1-1)+1) columns where every row is a path of T_1. On a
// run of length L where rows 1..j-1 are a path of T_{j-1}, rows 1..j are a path of the product
// T_{j-1} o T_1 (c_j components), hence of T_j on a sub-run of length >= (L - c_j + 1) / c_j.
// The product at level k has no cycle (T_k is empty), so a path in it has at most c_k - 1 steps.
// Unwinding: n <= (k(c_1-1)+1) * c_2 * ... * c_k - 1. So no square larger than
// max(k-1, that) is tileable.
#include <cstdint>
#include <optional>
#include <vector>

#include "aperiodic/transducer.hpp"
#include "tilesets/tile.hpp"

namespace tilekit {

struct ChainLevel {
  Transducer t;                     // T_k after trimming (and merging)
  std::vector<std::uint64_t> keys;  // k >= 2: product states p * |T_1| + q kept by the trim, sorted
  std::vector<std::uint32_t> cls;   // k >= 2: the state of t each of them became
  std::uint64_t components = 0;     // strongly connected components of the product (k = 1: of T)
  std::uint64_t product_states = 0, product_transitions = 0;  // before trimming
  double seconds = 0;
};

struct SquareBound {
  std::optional<std::uint64_t> side;  // the largest side a tileable square can have; nullopt: over 2^64
  double log10 = 0;                   // log10 of the bound (also when it overflows)
};

class TransducerChain {
 public:
  TransducerChain() = default;
  // `tiles` distinct; columns = true builds the chain of the transposed set (strips of columns).
  // Builds T_1; throws Stopped when the budget says so.
  TransducerChain(const std::vector<WangTile>& tiles, bool columns, bool merge, const Budget& budget = {});

  bool columns() const { return columns_; }
  bool merge() const { return merge_; }
  int k() const { return int(levels_.size()); }
  const ChainLevel& level(int k) const { return levels_.at(std::size_t(k) - 1); }
  // T_k is empty: no strip of k rows (columns) is infinite, so the set tiles no large square.
  bool finite() const { return !levels_.empty() && levels_.back().t.empty(); }

  // Builds T_{k+1}. Throws Stopped when the budget says so, leaving the chain as it was.
  void extend(const Budget& budget);

  // A cycle of T_k (k = this->k()) whose output word is its input word moved `shift` letters
  // (out_i == in_{i+shift}; shift 0: the same word), lifted to tiles: k rows, bottom first, of
  // equal width, each a cyclic row of tile numbers (positions in `tiles`) that matches its
  // neighbours, the top row's north word equal to the bottom row's south word moved by `shift`.
  // Stacking such strips, each moved `shift` columns, tiles the plane periodically. Shifts
  // 0, +-1, ..., +-max_shift are tried (a non-zero shift only where its delay-line product is
  // small). Empty rows when T_k has no such cycle. Throws Stopped like extend().
  struct Strip {
    std::vector<std::vector<std::uint32_t>> rows;
    int shift = 0;
  };
  Strip periodic_strip(const Budget& budget, int max_shift = 2) const;

  SquareBound square_bound() const;
  std::size_t bytes() const;

  // For checkpoints (aperiodic/decide_checkpoint.hpp): the levels as they are, and a chain
  // rebuilt from the tiles with the given levels (InputError unless they fit the tiles).
  const std::vector<ChainLevel>& levels() const { return levels_; }
  static TransducerChain restore(const std::vector<WangTile>& tiles, bool columns, bool merge,
                                 std::vector<ChainLevel> levels);
  // Builds T_1 .. T_k again from the tiles and compares them with the levels held: false when any
  // differs (a restored chain that is not the one the tiles give). Throws Stopped like extend().
  bool rederives(const Budget& budget) const;

 private:
  struct Step {
    std::uint32_t from, in, out, to;
  };
  // Lifts a cycle of T_j (steps in order, closed) to rows of tiles, bottom first.
  std::vector<std::vector<std::uint32_t>> lift(int j, const std::vector<Step>& cycle, const Budget& budget) const;
  // Checks a level read from a checkpoint (InputError) and rebuilds its index.
  void check_level(ChainLevel& l, int k) const;

  std::vector<WangTile> tiles_;  // as given (tile numbers), oriented
  Transducer base_;              // T: states = E/W colours, labels = N/S colours (dense)
  std::uint32_t labels_ = 0;
  bool columns_ = false, merge_ = true;
  std::vector<ChainLevel> levels_;
  std::vector<std::pair<Transition, std::uint32_t>> tile_of_;  // T_1 transition -> tile number, sorted
};

}  // namespace tilekit
