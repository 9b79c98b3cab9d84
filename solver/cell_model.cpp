#include "solver/cell_model.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cassert>
#include <numeric>

#include "base/error.hpp"

namespace tilekit {

namespace {
constexpr int kN = 0, kE = 1, kS = 2, kW = 3;
constexpr int opposite(int d) {
  return (d + 2) & 3;
}
}  // namespace

struct CellModel::Tables {
  TilingProblem problem;
  int rows = 0, cols = 0, labels = 0;
  std::vector<int> tile_label;  // tile number*4 + dir -> label
  std::vector<int> nb;          // cell*4 + dir -> neighbour cell or -1
  std::vector<int> order;       // static order of the free cells
  std::vector<char> self_ok;    // tile number -> fits next to itself where the torus is 1 wide
  std::vector<int> cls;         // cell -> residue class (0 without a class period)
  std::vector<int> class_start, class_cells;  // CSR: class -> its cells
};

CellModel::CellModel(const TilingProblem& p, bool break_translation, Ordering ordering, int class_period)
    : ordering_(ordering) {
  auto t = std::make_shared<Tables>();
  t->problem = p;
  t->rows = p.rows;
  t->cols = p.cols;
  const TileSet& set = p.set;
  tiles_ = int(set.size());
  cells_ = p.rows * p.cols;
  words_ = (tiles_ + 63) / 64;
  packing_ = p.packing;
  break_translation_ = break_translation && p.packing && p.torus;
  // Edge labels: Wang colours, or pairs of corner colours (thesis sec. 2.9).
  t->tile_label.resize(std::size_t(tiles_) * 4);
  if (set.kind() == TileKind::Wang) {
    const auto& w = set.wang_tiles();
    t->labels = int(std::max(set.horizontal_radix(), set.vertical_radix()));
    for (int k = 0; k < tiles_; ++k) {
      int* l = &t->tile_label[std::size_t(k) * 4];
      l[kN] = int(w[k].n), l[kE] = int(w[k].e), l[kS] = int(w[k].s), l[kW] = int(w[k].w);
    }
  } else {
    const auto& c = set.corner_tiles();
    int C = int(set.horizontal_radix());
    t->labels = C * C;
    for (int k = 0; k < tiles_; ++k) {
      int* l = &t->tile_label[std::size_t(k) * 4];
      l[kN] = int(c[k].nw) * C + int(c[k].ne);
      l[kS] = int(c[k].sw) * C + int(c[k].se);
      l[kW] = int(c[k].nw) * C + int(c[k].sw);
      l[kE] = int(c[k].ne) * C + int(c[k].se);
    }
  }
  // The compatibility masks: one bit per tile for every (direction, edge label).
  const std::uint64_t mask_words = 4 * std::uint64_t(t->labels) * std::uint64_t(words_);
  if (mask_words > kMaxModelTable)
    throw InputError(fmt::format("the cell model needs {} mask words for {} tiles and {} edge labels (limit {})",
                                 mask_words, tiles_, t->labels, kMaxModelTable));
  t->nb.assign(std::size_t(cells_) * 4, -1);
  for (int r = 0; r < p.rows; ++r)
    for (int c = 0; c < p.cols; ++c) {
      int* n = &t->nb[std::size_t(r * p.cols + c) * 4];
      auto at = [&](int rr, int cc) {
        if (p.torus) return ((rr + p.rows) % p.rows) * p.cols + (cc + p.cols) % p.cols;
        return (rr < 0 || rr >= p.rows || cc < 0 || cc >= p.cols) ? -1 : rr * p.cols + cc;
      };
      n[kN] = at(r - 1, c), n[kE] = at(r, c + 1), n[kS] = at(r + 1, c), n[kW] = at(r, c - 1);
    }
  // A 1-wide torus makes a cell its own neighbour: only tiles matching themselves fit.
  t->self_ok.assign(std::size_t(tiles_), 1);
  for (int k = 0; k < tiles_; ++k) {
    const int* l = &t->tile_label[std::size_t(k) * 4];
    if (p.torus && p.rows == 1 && l[kN] != l[kS]) t->self_ok[std::size_t(k)] = 0;
    if (p.torus && p.cols == 1 && l[kE] != l[kW]) t->self_ok[std::size_t(k)] = 0;
  }
  assert(class_period == 0 || (p.torus && p.packing && p.rows % class_period == 0 && p.cols % class_period == 0));
  classes_ = class_period > 0 ? class_period * class_period : 1;
  t->cls.resize(std::size_t(cells_));
  std::vector<std::vector<int>> members(static_cast<std::size_t>(classes_));
  for (int c = 0; c < cells_; ++c) {
    const int k = class_period > 0 ? (c / p.cols % class_period) * class_period + c % p.cols % class_period : 0;
    t->cls[std::size_t(c)] = k;
    members[std::size_t(k)].push_back(c);
  }
  t->class_start.push_back(0);
  for (const auto& m : members) {
    t->class_cells.insert(t->class_cells.end(), m.begin(), m.end());
    t->class_start.push_back(int(t->class_cells.size()));
  }
  // Every label is in range, so the masks below are indexed within bounds.
  assert(std::all_of(t->tile_label.begin(), t->tile_label.end(), [&](int l) { return l >= 0 && l < t->labels; }));
  fixed_ = break_translation_ ? 1 : 0;
  // Most constrained first keeps its frontier sorted by domain size when an assignment changes
  // few domains: tilings (neighbours only) and packings with small classes (lifts); a plain
  // packing changes every domain at each step, so it scans instead.
  incremental_ = ordering_ == Ordering::MostConstrained && (!packing_ || cells_ / classes_ <= 64);
  for (int c = fixed_; c < cells_; ++c) t->order.push_back(c);  // scanline from (0,0); MRV relies on it
  t_ = std::move(t);
  tile_.assign(std::size_t(cells_), -1);
  scratch_.resize(std::size_t(words_) * 2);
  set_value_seed(0);
}

void CellModel::set_value_seed(std::uint64_t seed) {
  perm_.resize(std::size_t(tiles_));
  std::iota(perm_.begin(), perm_.end(), 0);
  if (seed != 0) {
    SplitMix64 rng(mix_seed(seed));
    shuffle(perm_.begin(), perm_.end(), rng);
  }
  rebuild_masks();
}

void CellModel::rebuild_masks() {
  const Tables& t = *t_;
  label_.resize(std::size_t(tiles_) * 4);
  masks_.assign(4 * std::size_t(t.labels) * std::size_t(words_), 0);
  avail_.assign(std::size_t(words_) * std::size_t(classes_), 0);
  for (int v = 0; v < tiles_; ++v) {
    int k = perm_[std::size_t(v)];
    for (int d = 0; d < 4; ++d) {
      int l = t.tile_label[std::size_t(k) * 4 + std::size_t(d)];
      label_[std::size_t(v) * 4 + std::size_t(d)] = l;
      masks_[(std::size_t(d) * std::size_t(t.labels) + std::size_t(l)) * std::size_t(words_) + std::size_t(v / 64)] |=
          std::uint64_t(1) << (v % 64);
    }
    if (t.self_ok[std::size_t(k)])
      for (int c = 0; c < classes_; ++c) avail_[std::size_t(c * words_ + v / 64)] |= std::uint64_t(1) << (v % 64);
  }
  std::fill(tile_.begin(), tile_.end(), -1);
  assigned_ = 0;
  first_free_ = 0;
  frontier_.clear();
  frontier_key_.assign(std::size_t(cells_), -1);
  if (break_translation_) {
    int v0 = int(std::find(perm_.begin(), perm_.end(), 0) - perm_.begin());
    assign(0, v0);  // the fixed tile; never a decision
  }
}

int CellModel::domain(int cell, std::uint64_t* dom) const {
  const Tables& t = *t_;
  std::copy_n(avail_.data() + std::size_t(t.cls[std::size_t(cell)] * words_), words_, dom);
  const int* n = &t.nb[std::size_t(cell) * 4];
  for (int d = 0; d < 4; ++d) {
    int o = n[d];
    if (o < 0 || o == cell || tile_[std::size_t(o)] < 0) continue;
    int l = label_[std::size_t(tile_[std::size_t(o)]) * 4 + std::size_t(opposite(d))];
    const std::uint64_t* m = &masks_[std::size_t((d * t.labels + l) * words_)];
    for (int w = 0; w < words_; ++w) dom[w] &= m[w];
  }
  int size = 0;
  for (int w = 0; w < words_; ++w) size += std::popcount(dom[w]);
  return size;
}

bool CellModel::domain_empty(int cell) const {
  const Tables& t = *t_;
  const int* n = &t.nb[std::size_t(cell) * 4];
  const std::uint64_t* m[4];
  int k = 0;
  for (int d = 0; d < 4; ++d) {
    int o = n[d];
    if (o < 0 || o == cell || tile_[std::size_t(o)] < 0) continue;
    int l = label_[std::size_t(tile_[std::size_t(o)]) * 4 + std::size_t(opposite(d))];
    m[k++] = &masks_[std::size_t((d * t.labels + l) * words_)];
  }
  const std::uint64_t* avail = avail_.data() + std::size_t(t.cls[std::size_t(cell)] * words_);
  for (int w = 0; w < words_; ++w) {
    std::uint64_t x = avail[w];
    for (int i = 0; i < k; ++i) x &= m[i][w];
    if (x) return false;
  }
  return true;
}

int CellModel::branch(std::vector<int>& values) {
  values.clear();
  if (assigned_ == cells_) return -1;
  const Tables& t = *t_;
  int cell = -1;
  std::uint64_t* dom = scratch_.data();
  if (ordering_ == Ordering::Static) {
    cell = t.order[std::size_t(assigned_ - fixed_)];
    domain(cell, dom);
  } else if (incremental_ && assigned_ > 0) {
    if (!frontier_.empty()) {
      cell = frontier_.begin()->second;  // smallest domain, then lowest index: what the scan below picks
      domain(cell, dom);
    } else {
      for (int c : t.order)
        if (tile_[std::size_t(c)] < 0) {
          cell = c;
          break;
        }
      domain(cell, dom);
    }
  } else {
    // Most constrained first (smallest domain) among free cells next to a placed tile;
    // ties go to the static order.
    int best = tiles_ + 1;
    std::uint64_t* tmp = scratch_.data() + words_;
    for (int c = std::max(first_free_, fixed_); c < cells_; ++c) {  // t.order from the first free cell
      if (tile_[std::size_t(c)] >= 0) continue;
      if (assigned_ > 0) {
        const int* n = &t.nb[std::size_t(c) * 4];
        bool frontier = false;
        for (int d = 0; d < 4; ++d) frontier |= n[d] >= 0 && tile_[std::size_t(n[d])] >= 0;
        if (!frontier) continue;
      }
      int s = domain(c, tmp);
      if (s < best) {
        best = s, cell = c;
        std::copy_n(tmp, words_, dom);
        if (s <= 1) break;
      }
    }
    if (cell < 0) {  // bounded grids may have no frontier cell left: take the first free one
      for (int c : t.order)
        if (tile_[std::size_t(c)] < 0) {
          cell = c;
          break;
        }
      domain(cell, dom);
    }
  }
  assert(cell >= 0 && tile_[std::size_t(cell)] < 0);  // branch on a free cell only
  for (int w = 0; w < words_; ++w)
    for (std::uint64_t x = dom[w]; x; x &= x - 1) values.push_back(w * 64 + std::countr_zero(x));
  return cell;
}

bool CellModel::assign(int cell, int v) {
  const Tables& t = *t_;
  // The engine only assigns a free cell a value branch() offered (or the fixed tile): an
  // unplaced tile of the set, still available when the problem is a packing.
  assert(cell >= 0 && cell < cells_ && tile_[std::size_t(cell)] < 0);
  assert(v >= 0 && v < tiles_);
  assert(!packing_ || (avail_[std::size_t(t.cls[std::size_t(cell)] * words_ + v / 64)] >> (v % 64) & 1) || (break_translation_ && assigned_ == 0));
  tile_[std::size_t(cell)] = v;
  ++assigned_;
  while (first_free_ < cells_ && tile_[std::size_t(first_free_)] >= 0) ++first_free_;
  const int k = t.cls[std::size_t(cell)];
  if (packing_) avail_[std::size_t(k * words_ + v / 64)] &= ~(std::uint64_t(1) << (v % 64));
  if (incremental_) refresh_around(cell);
  // Forward checking: every free neighbour must keep a candidate.
  const int* n = &t.nb[std::size_t(cell) * 4];
  for (int d = 0; d < 4; ++d) {
    int o = n[d];
    if (o < 0 || tile_[std::size_t(o)] >= 0) continue;
    ++stats_.propagations;
    if (domain_empty(o)) {
      stats_.prune(Prune::ForwardCheck);
      return false;
    }
  }
  if (classes_ > 1)  // the tile is gone from the rest of its class too
    for (int i = t.class_start[std::size_t(k)]; i < t.class_start[std::size_t(k) + 1]; ++i) {
      const int o = t.class_cells[std::size_t(i)];
      if (tile_[std::size_t(o)] >= 0) continue;
      ++stats_.propagations;
      if (domain_empty(o)) {
        stats_.prune(Prune::ClassCheck);
        return false;
      }
    }
  return true;
}

void CellModel::unassign(int cell, int v) {
  assert(cell >= 0 && cell < cells_ && tile_[std::size_t(cell)] == v && assigned_ > 0);  // LIFO undo
  tile_[std::size_t(cell)] = -1;
  --assigned_;
  first_free_ = std::min(first_free_, cell);
  if (packing_) avail_[std::size_t(t_->cls[std::size_t(cell)] * words_ + v / 64)] |= std::uint64_t(1) << (v % 64);
  if (incremental_) refresh_around(cell);
}

void CellModel::refresh(int cell) {
  const Tables& t = *t_;
  int key = -1;
  if (tile_[std::size_t(cell)] < 0) {
    const int* n = &t.nb[std::size_t(cell) * 4];
    bool frontier = false;
    for (int d = 0; d < 4; ++d) frontier |= n[d] >= 0 && tile_[std::size_t(n[d])] >= 0;
    if (frontier) key = domain(cell, scratch_.data() + words_);
  }
  int& old = frontier_key_[std::size_t(cell)];
  if (key == old) return;
  if (old >= 0) frontier_.erase({old, cell});
  if (key >= 0) frontier_.insert({key, cell});
  old = key;
}

void CellModel::refresh_around(int cell) {
  const Tables& t = *t_;
  refresh(cell);
  const int* n = &t.nb[std::size_t(cell) * 4];
  for (int d = 0; d < 4; ++d)
    if (n[d] >= 0) refresh(n[d]);
  if (packing_) {  // the class's available tiles changed (incremental_ implies small classes)
    const int k = t.cls[std::size_t(cell)];
    for (int i = t.class_start[std::size_t(k)]; i < t.class_start[std::size_t(k) + 1]; ++i)
      refresh(t.class_cells[std::size_t(i)]);
  }
}

Tiling CellModel::tiling() const {
  const TileSet& set = t_->problem.set;
  Tiling out(set.kind(), set.horizontal_radix(), t_->rows, t_->cols, t_->problem.torus);
  if (set.kind() == TileKind::Wang) out.vertical_colours = set.vertical_radix();
  for (int c = 0; c < cells_; ++c) {
    int v = tile_[std::size_t(c)];
    out.cells[std::size_t(c)] = v < 0 ? 0 : set.index_of(std::size_t(perm_[std::size_t(v)]));
  }
  return out;
}

}  // namespace tilekit
