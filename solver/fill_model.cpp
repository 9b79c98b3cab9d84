#include "solver/fill_model.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cassert>
#include <cmath>
#include <utility>

#include "base/error.hpp"
#include "base/random.hpp"

namespace tilekit {

FillRules::FillRules(int tiles, std::vector<double> weights) : tiles_(tiles), weights_(std::move(weights)) {
  if (tiles < 1 || tiles > kMaxFillTiles)
    throw InputError(fmt::format("a fill set has 1 to {} tiles, got {}", kMaxFillTiles, tiles));
  if (weights_.empty()) weights_.assign(std::size_t(tiles), 1.0);
  if (weights_.size() != std::size_t(tiles))
    throw InputError(fmt::format("{} weights for {} tiles", weights_.size(), tiles));
  for (double w : weights_)
    if (!(w > 0) || !std::isfinite(w)) throw InputError(fmt::format("tile weight {} is not a positive number", w));
  words_ = (tiles + 63) / 64;
  allow_.assign(std::size_t(tiles) * kFillDirs * std::size_t(words_), 0);
}

void FillRules::allow(int a, int d, int b) {
  assert(a >= 0 && a < tiles_ && b >= 0 && b < tiles_ && d >= 0 && d < kFillDirs);
  auto set = [&](int x, int dir, int y) {
    allow_[(std::size_t(x) * kFillDirs + std::size_t(dir)) * std::size_t(words_) + (std::size_t(y) >> 6)] |=
        std::uint64_t(1) << (y & 63);
  };
  set(a, d, b);
  set(b, fill_opposite(d), a);
}

FillModel::FillModel(const FillRegion& region)
    : rules_(region.rules),
      rows_(region.rows),
      cols_(region.cols),
      cells_(region.rows * region.cols),
      words_(region.rules->words()),
      wrap_rows_(region.wrap_rows),
      wrap_cols_(region.wrap_cols) {
  if (rows_ < 1 || cols_ < 1) throw InputError(fmt::format("a fill region of {}x{} cells", rows_, cols_));
  mode_ = region.order == FillOrder::Entropy ? FillOrder::Entropy : FillOrder::Scanline;
  filled_near_.assign(std::size_t(cells_), 0);
  for (int t = 0; t < rules_->tiles(); ++t) {
    wlogw_.push_back(rules_->weight(t) * std::log(rules_->weight(t)));
    if (rules_->weight(t) != rules_->weight(0)) equal_weights_ = false;
  }
  const std::size_t n = std::size_t(cells_) * std::size_t(words_);
  if (!region.domains.empty() && region.domains.size() != n)
    throw InputError("a fill region's domains do not match its size");
  dom_.assign(n, 0);
  const int tiles = rules_->tiles();
  for (int c = 0; c < cells_; ++c) {
    std::uint64_t* d = &dom_[std::size_t(c) * std::size_t(words_)];
    for (int t = 0; t < tiles; ++t) d[t >> 6] |= std::uint64_t(1) << (t & 63);
    if (!region.domains.empty())
      for (int w = 0; w < words_; ++w) d[w] &= region.domains[std::size_t(c) * std::size_t(words_) + std::size_t(w)];
  }
  count_.assign(std::size_t(cells_), 0);
  assigned_.assign(std::size_t(cells_), 0);
  queued_.assign(std::size_t(cells_), 0);
  scratch_.assign(std::size_t(words_), 0);
  for (int c = 0; c < cells_; ++c) {
    int k = 0;
    for (int w = 0; w < words_; ++w) k += std::popcount(dom_[std::size_t(c) * std::size_t(words_) + std::size_t(w)]);
    count_[std::size_t(c)] = k;
    if (k == 0 && wiped_ < 0) wiped_ = c;
  }
  // a cell that is its own neighbour (a torus one cell wide or high) holds only tiles that may touch themselves
  for (int c = 0; c < cells_ && wiped_ < 0; ++c)
    for (int d = 0; d < kFillDirs; ++d)
      if (neighbour(c, d) == c) {
        std::uint64_t* dc = &dom_[std::size_t(c) * std::size_t(words_)];
        int k = 0;
        for (int t = 0; t < tiles; ++t)
          if (((dc[t >> 6] >> (t & 63)) & 1) && !rules_->allowed(t, d, t)) dc[t >> 6] &= ~(std::uint64_t(1) << (t & 63));
        for (int w = 0; w < words_; ++w) k += std::popcount(dc[w]);
        count_[std::size_t(c)] = k;
        if (k == 0) wiped_ = c;
      }
  if (wiped_ < 0) {
    for (int c = 0; c < cells_; ++c) {
      queue_.push_back(c);
      queued_[std::size_t(c)] = 1;
    }
    if (!propagate()) {
      for (int c = 0; c < cells_; ++c)
        if (count_[std::size_t(c)] == 0) {
          wiped_ = c;
          break;
        }
    }
  }
  if (region.cover) {
    cover_ = true;
    support_.assign(std::size_t(tiles), 0);
    for (int c = 0; c < cells_; ++c)
      for (int w = 0; w < words_; ++w) count_support(c, dom_[std::size_t(c) * std::size_t(words_) + std::size_t(w)], w, +1);
    if (cells_ < tiles && wiped_ < 0) wiped_ = 0;
    for (int t = 0; t < tiles && wiped_ < 0; ++t)
      if (support_[std::size_t(t)] == 0) wiped_ = 0;
  }
  trail_.clear();  // the root state is never undone
  set_value_seed(0);
}

std::uint64_t FillModel::tie(int cell) const {
  if (mode_ == FillOrder::Entropy) return mix_seed(seed_ ^ mix_seed(std::uint64_t(cell) + 0x9e3779b97f4a7c15ull));
  return std::uint64_t(cell);  // scanline among equals: a block grows from its filled borders
}

// WFC's entropy of a cell: log(sum w) - (sum w log w) / (sum w) over the tiles left (Gumin,
// WaveFunctionCollapse, Model.cs). With equal weights it is log(count): the count orders alike.
double FillModel::rank(int cell) const {
  const int n = count_[std::size_t(cell)];
  if (mode_ == FillOrder::Scanline) return double(n);
  // Entropy: the frontier first (cells beside a filled one or with tiles ruled out), so that one
  // region grows; WFC's order over the whole map starts islands that collide on large maps.
  const double away = filled_near_[std::size_t(cell)] > 0 || n < rules_->tiles() ? 0 : 1e6;
  if (equal_weights_ || n <= 1) return away + double(n);
  const std::uint64_t* d = &dom_[std::size_t(cell) * std::size_t(words_)];
  double sw = 0, swl = 0;
  for (int w = 0; w < words_; ++w)
    for (std::uint64_t bits = d[w]; bits; bits &= bits - 1) {
      const int t = w * 64 + std::countr_zero(bits);
      sw += rules_->weight(t);
      swl += wlogw_[std::size_t(t)];
    }
  return away + std::log(sw) - swl / sw;
}

void FillModel::set_value_seed(std::uint64_t seed) {
  seed_ = seed;
  rebuild_order();
}

void FillModel::rebuild_order() {
  std::vector<Key> keys;
  keys.reserve(std::size_t(cells_));
  for (int c = 0; c < cells_; ++c)
    if (!assigned_[std::size_t(c)]) keys.emplace_back(rank(c), tie(c), c, count_[std::size_t(c)]);
  order_ = decltype(order_)(std::greater<Key>(), std::move(keys));
}

void FillModel::push_key(int cell) {
  if (order_.size() > 8 * std::size_t(cells_) + 1024) rebuild_order();  // too many stale entries
  order_.emplace(rank(cell), tie(cell), cell, count_[std::size_t(cell)]);
}

int FillModel::neighbour(int cell, int d) const {
  int r = cell / cols_, c = cell % cols_;
  switch (d) {
    case 0: r -= 1; break;
    case 1: c += 1; break;
    case 2: r += 1; break;
    default: c -= 1; break;
  }
  if (r < 0 || r >= rows_) {
    if (!wrap_rows_) return -1;
    r = (r + rows_) % rows_;
  }
  if (c < 0 || c >= cols_) {
    if (!wrap_cols_) return -1;
    c = (c + cols_) % cols_;
  }
  return r * cols_ + c;
}

void FillModel::count_support(int, std::uint64_t bits, int word, int delta) {
  for (; bits; bits &= bits - 1) {
    int& k = support_[std::size_t(word * 64 + std::countr_zero(bits))];
    k += delta;
    if (k == 0) cover_failed_ = true;
  }
}

void FillModel::set_count(int cell, int n) {
  int& k = count_[std::size_t(cell)];
  if (k == n) return;
  k = n;
  if (!assigned_[std::size_t(cell)]) push_key(cell);
}

bool FillModel::restrict(int cell, const std::uint64_t* keep) {
  std::uint64_t* d = &dom_[std::size_t(cell) * std::size_t(words_)];
  bool changed = false;
  int n = 0;
  for (int w = 0; w < words_; ++w) {
    const std::uint64_t nw = d[w] & keep[w];
    if (nw != d[w]) {
      trail_.push_back({std::uint32_t(std::size_t(cell) * std::size_t(words_) + std::size_t(w)), d[w]});
      if (cover_) count_support(cell, d[w] & ~nw, w, -1);
      d[w] = nw;
      changed = true;
    }
    n += std::popcount(nw);
  }
  if (!changed) return true;
  ++stats_.propagations;
  set_count(cell, n);
  if (n == 0) return false;
  if (cover_failed_) {
    stats_.prune(Prune::ClassCheck);
    return false;
  }
  if (!queued_[std::size_t(cell)]) {
    queued_[std::size_t(cell)] = 1;
    queue_.push_back(cell);
  }
  return true;
}

bool FillModel::propagate() {
  const int tiles = rules_->tiles();
  while (!queue_.empty()) {
    const int x = queue_.back();
    queue_.pop_back();
    queued_[std::size_t(x)] = 0;
    const std::uint64_t* dx = &dom_[std::size_t(x) * std::size_t(words_)];
    const bool full = count_[std::size_t(x)] == tiles;
    for (int d = 0; d < kFillDirs; ++d) {
      const int y = neighbour(x, d);
      if (y < 0 || full) continue;
      std::fill(scratch_.begin(), scratch_.end(), 0);
      for (int w = 0; w < words_; ++w)
        for (std::uint64_t bits = dx[w]; bits; bits &= bits - 1) {
          const int a = w * 64 + std::countr_zero(bits);
          const std::uint64_t* m = rules_->mask(a, d);
          for (int v = 0; v < words_; ++v) scratch_[std::size_t(v)] |= m[v];
        }
      if (!restrict(y, scratch_.data())) {
        stats_.prune(Prune::ForwardCheck);
        for (int q : queue_) queued_[std::size_t(q)] = 0;
        queue_.clear();
        return false;
      }
    }
  }
  return true;
}

int FillModel::branch(std::vector<int>& values) {
  values.clear();
  while (!order_.empty()) {
    const auto& [r, h, c, k] = order_.top();
    if (!assigned_[std::size_t(c)] && k == count_[std::size_t(c)]) break;
    order_.pop();
  }
  if (order_.empty()) return -1;
  const int cell = std::get<2>(order_.top());
  const std::uint64_t* d = &dom_[std::size_t(cell) * std::size_t(words_)];
  std::vector<std::pair<double, int>>& keyed = keyed_;
  keyed.clear();
  for (int w = 0; w < words_; ++w)
    for (std::uint64_t bits = d[w]; bits; bits &= bits - 1) {
      const int t = w * 64 + std::countr_zero(bits);
      double key = t;
      if (seed_ != 0) {
        const std::uint64_t h = mix_seed(seed_ ^ mix_seed(std::uint64_t(cell) * 0x100000001b3ull + std::uint64_t(t)));
        const double u = (double(h >> 11) + 0.5) * 0x1.0p-53;  // in (0, 1)
        key = -std::log(u) / rules_->weight(t);
      }
      keyed.emplace_back(key, t);
    }
  std::sort(keyed.begin(), keyed.end());
  values.reserve(keyed.size());
  for (const auto& [k, t] : keyed) values.push_back(t);
  return cell;
}

bool FillModel::assign(int cell, int tile) {
  assert(!assigned_[std::size_t(cell)]);
  marks_.push_back(trail_.size());
  assigned_[std::size_t(cell)] = 1;
  single_.assign(std::size_t(words_), 0);
  single_[std::size_t(tile) >> 6] = std::uint64_t(1) << (tile & 63);
  if (mode_ == FillOrder::Entropy)
    for (int d = 0; d < kFillDirs; ++d)
      if (const int y = neighbour(cell, d); y >= 0 && ++filled_near_[std::size_t(y)] == 1 && !assigned_[std::size_t(y)])
        push_key(y);
  if (!restrict(cell, single_.data())) return false;
  if (!queued_[std::size_t(cell)]) {
    queued_[std::size_t(cell)] = 1;
    queue_.push_back(cell);
  }
  return propagate();
}

void FillModel::unassign(int cell, int /*tile*/) {
  assert(!marks_.empty());
  const std::size_t mark = marks_.back();
  marks_.pop_back();
  while (trail_.size() > mark) {
    const Change ch = trail_.back();
    trail_.pop_back();
    if (cover_) count_support(int(ch.word / std::uint32_t(words_)), ch.old & ~dom_[ch.word], int(ch.word % std::uint32_t(words_)), +1);
    dom_[ch.word] = ch.old;
    const int c = int(ch.word / std::uint32_t(words_));
    int n = 0;
    for (int w = 0; w < words_; ++w) n += std::popcount(dom_[std::size_t(c) * std::size_t(words_) + std::size_t(w)]);
    set_count(c, n);
  }
  assigned_[std::size_t(cell)] = 0;
  if (mode_ == FillOrder::Entropy)
    for (int d = 0; d < kFillDirs; ++d)
      if (const int y = neighbour(cell, d); y >= 0) --filled_near_[std::size_t(y)];
  cover_failed_ = false;
  push_key(cell);
}

Tiling FillModel::tiling() const {
  Tiling t;
  t.rows = rows_;
  t.cols = cols_;
  t.torus = wrap_rows_ && wrap_cols_;
  t.cells.assign(std::size_t(cells_), 0);
  for (int c = 0; c < cells_; ++c) {
    const std::uint64_t* d = &dom_[std::size_t(c) * std::size_t(words_)];
    for (int w = 0; w < words_; ++w)
      if (d[w]) {
        t.cells[std::size_t(c)] = TileIndex(w * 64 + std::countr_zero(d[w]));
        break;
      }
  }
  return t;
}

}  // namespace tilekit
