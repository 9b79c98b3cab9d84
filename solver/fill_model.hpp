#pragma once
// The map-filling model (`tilekit fill`): one variable per cell of a W x H region, whose values
// are the tiles of any set with adjacency rules (a Wang or corner set, a Tiled Wang set, the
// simple tiled model of Wave Function Collapse). Unlike CellModel it needs no edge colours: the
// rules are, per tile and direction, the set of tiles allowed next to it.
//
// Domains are bitsets over the tiles. Every assignment is propagated to arc consistency (AC-3
// over the four neighbours: a tile stays in a cell's domain only while every neighbour's domain
// holds a tile it may touch), undone from a trail in LIFO order. Branching: most constrained
// cell first (fewest tiles left), ties broken by a hash of the value seed and the cell; values
// in a weighted random order (keys -log(u)/w, u a hash of seed, cell and tile: Efraimidis and
// Spirakis 2006, so a dive samples tiles in proportion to their weights), or in tile order for
// seed 0. Both are functions of the assignment and the seed, as the engine requires.
//
// A region is part of a map (solver/fill_search.hpp fills large maps block by block): cells
// outside it that are already filled enter as the initial domains of the cells next to them,
// and a region wraps in a direction only when it spans the whole torus in that direction.
#include <cstdint>
#include <memory>
#include <queue>
#include <string>
#include <tuple>
#include <vector>

#include "solver/model.hpp"
#include "solver/search_stats.hpp"

namespace tilekit {

// Directions of the rules: 0 north (row - 1), 1 east (col + 1), 2 south, 3 west.
inline constexpr int kFillDirs = 4;
inline constexpr int fill_opposite(int d) { return (d + 2) & 3; }

// The most tiles a fill set may have (64 mask words per domain).
inline constexpr int kMaxFillTiles = 4096;

// Which tiles may sit next to which: allowed(a, d) is the bitset of tiles b that may be the
// neighbour of a in direction d. Built symmetric: b in allowed(a, d) iff a in allowed(b, opposite d).
class FillRules {
 public:
  // InputError for 0 or more than kMaxFillTiles tiles, or a weight that is not a positive finite number.
  FillRules(int tiles, std::vector<double> weights);
  // Allows b next to a in direction d (and a next to b in the opposite direction).
  void allow(int a, int d, int b);
  bool allowed(int a, int d, int b) const {
    return (mask(a, d)[std::size_t(b) >> 6] >> (b & 63)) & 1u;
  }
  const std::uint64_t* mask(int a, int d) const {
    return &allow_[(std::size_t(a) * kFillDirs + std::size_t(d)) * std::size_t(words_)];
  }
  int tiles() const { return tiles_; }
  int words() const { return words_; }
  double weight(int t) const { return weights_[std::size_t(t)]; }

 private:
  int tiles_ = 0, words_ = 0;
  std::vector<double> weights_;
  std::vector<std::uint64_t> allow_;
};

// Which unassigned cell a dive fills next. Scanline: the fewest tiles left, ties in scanline
// order (a region grows from its filled borders). Entropy: the least Shannon entropy of the
// weights left (Gumin's WaveFunctionCollapse; the fewest tiles when the weights are equal) among
// the frontier (cells beside a filled one or with tiles ruled out; elsewhere only when it is
// empty), ties by seeded noise: one region grows in a random order rather than a scan from a
// corner (WFC's order over the whole map starts islands that collide on large maps).
// Auto (a map request only, solver/fill_search.hpp): Entropy for a map searched as one region,
// Scanline for a map filled in blocks.
enum class FillOrder { Scanline, Entropy, Auto };

// One region to fill: rows x cols cells, each with an initial domain (empty vector: every tile).
struct FillRegion {
  std::shared_ptr<const FillRules> rules;
  int rows = 0, cols = 0;
  bool wrap_rows = false, wrap_cols = false;  // a torus in that direction
  std::vector<std::uint64_t> domains;         // rows*cols*words, or empty for every tile everywhere
  // Every tile at least once (a sheet that holds the whole set): a tile that no cell's domain
  // holds any more is a dead end (prune `TileUsed`'s counterpart, counted as ClassCheck).
  bool cover = false;
  FillOrder order = FillOrder::Scanline;
};

class FillModel {
 public:
  // Propagates the initial domains; consistent() is false when some cell has no tile left.
  explicit FillModel(const FillRegion& region);

  int branch(std::vector<int>& values);
  bool assign(int cell, int tile);
  void unassign(int cell, int tile);
  void set_value_seed(std::uint64_t seed);
  // At a leaf: cell r*cols + c holds its tile's index in the rules (kind and colours unset).
  Tiling tiling() const;
  std::uint64_t multiplicity() const { return 1; }
  ModelStats& stats() { return stats_; }

  bool consistent() const { return wiped_ < 0; }
  int wiped_cell() const { return wiped_; }  // the first cell left without a tile (-1: none)
  int count(int cell) const { return count_[std::size_t(cell)]; }

 private:
  bool propagate();  // from the cells on queue_; false on a wipeout
  bool restrict(int cell, const std::uint64_t* keep);  // dom &= keep (trailed); false when emptied
  void set_count(int cell, int n);
  std::uint64_t tie(int cell) const;
  double rank(int cell) const;  // the order's first key: tiles left, or the entropy of their weights
  int neighbour(int cell, int d) const;

  std::shared_ptr<const FillRules> rules_;
  int rows_ = 0, cols_ = 0, cells_ = 0, words_ = 0;
  bool wrap_rows_ = false, wrap_cols_ = false;
  std::uint64_t seed_ = 0;
  std::vector<std::uint64_t> dom_;
  std::vector<int> count_;
  std::vector<char> assigned_;
  struct Change {
    std::uint32_t word;  // cell * words + word index
    std::uint64_t old;
  };
  std::vector<Change> trail_;
  std::vector<std::size_t> marks_;  // trail size at each assign
  // (rank, tie, cell, count) of the unassigned cells, smallest first: a lazy heap, an entry pushed
  // at every change of a cell's count and dropped when it is stale (the cell assigned, its count changed)
  using Key = std::tuple<double, std::uint64_t, int, int>;
  FillOrder mode_ = FillOrder::Scanline;
  bool equal_weights_ = true;
  std::vector<double> wlogw_;     // w log w per tile (Entropy)
  std::vector<int> filled_near_;  // assigned neighbours per cell (Entropy: ties beside them first)
  std::priority_queue<Key, std::vector<Key>, std::greater<Key>> order_;
  void push_key(int cell);
  void rebuild_order();
  std::vector<std::pair<double, int>> keyed_;
  std::vector<std::uint64_t> single_;
  bool cover_ = false;
  std::vector<int> support_;  // cover: cells whose domain holds each tile
  void count_support(int cell, std::uint64_t removed, int word, int delta);
  bool cover_failed_ = false;
  std::vector<int> queue_;
  std::vector<char> queued_;
  std::vector<std::uint64_t> scratch_;
  int wiped_ = -1;
  ModelStats stats_;
};

static_assert(SearchModel<FillModel>);

}  // namespace tilekit
