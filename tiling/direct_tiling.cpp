#include "tiling/direct_tiling.hpp"

#include <numeric>
#include <vector>

#include "base/random.hpp"

namespace tilekit {

namespace {

// a + b modulo c for a, b < c
inline std::uint32_t add_mod(std::uint32_t a, std::uint32_t b, std::uint32_t c) {
  std::uint32_t s = a + b;
  return s >= c ? s - c : s;
}

Tiling wang_grid(std::uint32_t ch, std::uint32_t cv, int rows, int cols) {
  Tiling t(TileKind::Wang, ch, rows, cols, false);
  if (cv != ch) t.vertical_colours = cv;
  return t;
}

}  // namespace

Tiling DirectCornerTiling::generate(int rows, int cols, std::int64_t x0, std::int64_t y0) const {
  return lattice_corner_tiling(h_, rows, cols, x0, y0);
}

// ---- thesis sec. 3.3.2.1: two hashes --------------------------------------------------------

DirectWangTiling::DirectWangTiling(std::uint32_t ch, std::uint32_t cv, HashKind kind, std::uint64_t seed)
    : hh_(kind, ch, derive_seed(seed, 1)), hv_(kind, cv, derive_seed(seed, 2)) {}

TileIndex DirectWangTiling::tile(std::int64_t x, std::int64_t y) const {
  const std::uint32_t ch = hh_.colours(), cv = hv_.colours();
  // corners NW (x, y), NE (x+1, y), SW (x, y+1), SE (x+1, y+1); thesis sec. 3.3.2.1:
  // N = (h_h(NW) + h_h(NE)) % C_h, E = (h_v(NE) + h_v(SE)) % C_v, S = (h_h(SE) + h_h(SW)) % C_h,
  // W = (h_v(SW) + h_v(NW)) % C_v
  WangTile t;
  t.n = add_mod(hh_.colour(x, y), hh_.colour(x + 1, y), ch);
  t.e = add_mod(hv_.colour(x + 1, y), hv_.colour(x + 1, y + 1), cv);
  t.s = add_mod(hh_.colour(x + 1, y + 1), hh_.colour(x, y + 1), ch);
  t.w = add_mod(hv_.colour(x, y + 1), hv_.colour(x, y), cv);
  return wang_index(t, ch, cv);
}

void DirectWangTiling::fill(std::int64_t x0, std::int64_t y0, int rows, int cols, TileIndex* out) const {
  const std::uint32_t ch = hh_.colours(), cv = hv_.colours();
  const std::size_t n = std::size_t(cols) + 1;
  ColourHash::RowCache ch_cache, cv_cache;
  hh_.prepare(ch_cache, x0, n);
  hv_.prepare(cv_cache, x0, n);
  std::vector<std::uint16_t> nh(n), nv(n), sh(n), sv(n);
  hh_.row(ch_cache, y0, nh.data());
  hv_.row(cv_cache, y0, nv.data());
  for (int r = 0; r < rows; ++r) {
    hh_.row(ch_cache, y0 + r + 1, sh.data());
    hv_.row(cv_cache, y0 + r + 1, sv.data());
    TileIndex* o = out + std::size_t(r) * std::size_t(cols);
    for (int k = 0; k < cols; ++k) {
      const WangTile t{add_mod(nh[k], nh[k + 1], ch), add_mod(nv[k + 1], sv[k + 1], cv), add_mod(sh[k + 1], sh[k], ch),
                       add_mod(sv[k], nv[k], cv)};
      o[k] = wang_index(t, ch, cv);  // thesis eq. (2.2)
    }
    nh.swap(sh);
    nv.swap(sv);
  }
}

Tiling DirectWangTiling::generate(int rows, int cols, std::int64_t x0, std::int64_t y0) const {
  Tiling t = wang_grid(ch(), cv(), rows, cols);
  fill(x0, y0, rows, cols, t.cells.data());
  return t;
}

// ---- thesis sec. 3.3.2.2: compact sets, one hash --------------------------------------------

TileIndex DirectCompactWangTiling::tile(std::int64_t x, std::int64_t y) const {
  const std::uint32_t c = h_.colours();
  const std::uint32_t nw = h_.colour(x, y), ne = h_.colour(x + 1, y), sw = h_.colour(x, y + 1),
                      se = h_.colour(x + 1, y + 1);
  // thesis sec. 3.3.2.2: N = (NW + NE) % C, E = (NE + SE) % C, S = (SE + SW) % C, W = (SW + NW) % C
  return wang_index(WangTile{add_mod(nw, ne, c), add_mod(ne, se, c), add_mod(se, sw, c), add_mod(sw, nw, c)}, c);
}

void DirectCompactWangTiling::fill(std::int64_t x0, std::int64_t y0, int rows, int cols, TileIndex* out) const {
  const std::uint32_t c = h_.colours();
  const std::size_t n = std::size_t(cols) + 1;
  ColourHash::RowCache cache;
  h_.prepare(cache, x0, n);
  std::vector<std::uint16_t> north(n), south(n);
  h_.row(cache, y0, north.data());
  for (int r = 0; r < rows; ++r) {
    h_.row(cache, y0 + r + 1, south.data());
    TileIndex* o = out + std::size_t(r) * std::size_t(cols);
    for (int k = 0; k < cols; ++k) {
      const WangTile t{add_mod(north[k], north[k + 1], c), add_mod(north[k + 1], south[k + 1], c),
                       add_mod(south[k + 1], south[k], c), add_mod(south[k], north[k], c)};
      o[k] = wang_index(t, c);
    }
    north.swap(south);
  }
}

Tiling DirectCompactWangTiling::generate(int rows, int cols, std::int64_t x0, std::int64_t y0) const {
  Tiling t = wang_grid(colours(), colours(), rows, cols);
  fill(x0, y0, rows, cols, t.cells.data());
  return t;
}

// ---- thesis sec. 3.3.2.3: one hash at the tile edges ----------------------------------------

DirectEdgeWangTiling::DirectEdgeWangTiling(std::uint32_t ch, std::uint32_t cv, HashKind kind, std::uint64_t seed)
    : ch_(ch), cv_(cv), h_(kind, std::lcm(ch, cv), seed) {
  for (std::uint32_t v = 0; v < h_.colours(); ++v) {
    mod_h_.push_back(std::uint16_t(v % ch));
    mod_v_.push_back(std::uint16_t(v % cv));
  }
}

TileIndex DirectEdgeWangTiling::tile(std::int64_t x, std::int64_t y) const {
  // thesis sec. 3.3.2.3 (rows growing south): N = h(2x+1, 2y), E = h(2x+2, 2y+1),
  // S = h(2x+1, 2y+2), W = h(2x, 2y+1); the other five points of the 3x3 block are ignored.
  const WangTile t{h_.colour(2 * x + 1, 2 * y) % ch_, h_.colour(2 * x + 2, 2 * y + 1) % cv_,
                   h_.colour(2 * x + 1, 2 * y + 2) % ch_, h_.colour(2 * x, 2 * y + 1) % cv_};
  return wang_index(t, ch_, cv_);
}

void DirectEdgeWangTiling::fill(std::int64_t x0, std::int64_t y0, int rows, int cols, TileIndex* out) const {
  // Only the edge midpoints are evaluated (thesis sec. 3.3.2.3: "the remaining five random
  // colors are ignored"): odd dense columns 2x+1 on the even dense rows (N and S edges, each
  // row shared by two tile rows) and even dense columns 2x on the odd dense rows (E and W).
  const std::size_t n = std::size_t(cols);
  ColourHash::RowCache odd, even;
  h_.prepare(odd, 2 * x0 + 1, n, 2);
  h_.prepare(even, 2 * x0, n + 1, 2);
  std::vector<std::uint16_t> north(n), middle(n + 1), south(n);
  h_.row(odd, 2 * y0, north.data());
  for (int r = 0; r < rows; ++r) {
    h_.row(even, 2 * (y0 + r) + 1, middle.data());
    h_.row(odd, 2 * (y0 + r) + 2, south.data());
    TileIndex* o = out + std::size_t(r) * std::size_t(cols);
    for (std::size_t k = 0; k < n; ++k) {
      const WangTile t{mod_h_[north[k]], mod_v_[middle[k + 1]], mod_h_[south[k]], mod_v_[middle[k]]};
      o[k] = wang_index(t, ch_, cv_);
    }
    north.swap(south);
  }
}

Tiling DirectEdgeWangTiling::generate(int rows, int cols, std::int64_t x0, std::int64_t y0) const {
  Tiling t = wang_grid(ch_, cv_, rows, cols);
  fill(x0, y0, rows, cols, t.cells.data());
  return t;
}

// ---- the tiling of texture mapping ----------------------------------------------------------

DirectTiling::DirectTiling(TileKind kind, std::uint32_t colours, HashKind hash, std::uint64_t seed)
    : kind_(kind), hash_(hash), seed_(seed) {
  if (kind == TileKind::Corner)
    corner_ = std::make_unique<DirectCornerTiling>(colours, hash, seed);
  else
    wang_ = std::make_unique<DirectWangTiling>(colours, colours, hash, seed);
}

std::uint32_t DirectTiling::colours() const {
  return corner_ ? corner_->colours() : wang_->ch();
}

TileIndex DirectTiling::tile(std::int64_t x, std::int64_t y) const {
  return corner_ ? corner_->tile(x, y) : wang_->tile(x, y);
}

void DirectTiling::fill(std::int64_t x0, std::int64_t y0, int rows, int cols, TileIndex* out) const {
  if (corner_)
    corner_->fill(x0, y0, rows, cols, out);
  else
    wang_->fill(x0, y0, rows, cols, out);
}

std::vector<const ColourHash*> DirectTiling::hashes() const {
  if (corner_) return {&corner_->hash()};
  return {&wang_->horizontal_hash(), &wang_->vertical_hash()};
}

}  // namespace tilekit
