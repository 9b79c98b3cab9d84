#include "points/generator.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdlib>
#include <regex>

#include "base/error.hpp"
#include "base/parallel.hpp"
#include "base/progress.hpp"
#include "base/random.hpp"
#include "base/resources.hpp"
#include "base/signals.hpp"
#include "points/tile_parts.hpp"
#include "tiling/lattice_tiling.hpp"

namespace tilekit::points {

Window parse_window(const std::string& text, const char* what) {
  static const std::regex num(R"(\s*([-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?)\s*)");
  std::vector<double> v;
  std::size_t pos = 0;
  while (pos <= text.size() && v.size() < 5) {
    const std::size_t comma = text.find(',', pos);
    const std::string part = text.substr(pos, comma == std::string::npos ? std::string::npos : comma - pos);
    std::smatch m;
    if (!std::regex_match(part, m, num)) break;
    const double x = std::strtod(m[1].str().c_str(), nullptr);  // +-HUGE_VAL beyond double's range
    if (!std::isfinite(x)) break;
    v.push_back(x);
    if (comma == std::string::npos) break;
    pos = comma + 1;
  }
  // Finite coordinates can still give an infinite width, height or area (1e306 wide and tall).
  if (v.size() != 4 || !(v[0] < v[2]) || !(v[1] < v[3]) || !std::isfinite(v[2] - v[0]) || !std::isfinite(v[3] - v[1]) ||
      !std::isfinite((v[2] - v[0]) * (v[3] - v[1])))
    throw_input_error(what, fmt::format("{} must be x0,y0,x1,y1 with x0 < x1 and y0 < y1, got '{}'", what, text));
  return {v[0], v[1], v[2], v[3]};
}

struct PoissonTileGenerator::Scratch {
  std::vector<TileIndex> idx;
  std::vector<std::uint64_t> wide;  // edge-based tile indices
  ColourHash::RowCache h, v;        // edge colours along a row: horizontal, vertical edges
  std::vector<std::uint16_t> north, south, west;
};

PoissonTileGenerator::PoissonTileGenerator(const PoissonTileSet& set, HashKind hash, std::uint64_t seed,
                                           std::int64_t period)
    : set_(set), hash_(hash, set.lattice_colours(), seed), period_(period) {
  if (period < 0) throw RequestError("period", "`period` must be positive");
  // Edge colours from a second hash with its own seed, so that they do not repeat the lattice
  // colours (thesis sec. 3.3.2.3 hashes Wang edge colours the same way).
  if (set.edge_colours > 1) edge_hash_.emplace(hash, set.edge_colours, derive_seed(seed, 0x65646765));
  offset_.reserve(set.tiles.size() + 1);
  offset_.push_back(0);
  for (const auto& t : set.tiles) {
    for (const Point2& p : t) uv_.insert(uv_.end(), {p.x, p.y});
    offset_.push_back(std::uint32_t(uv_.size() / 2));
  }
  for (double u : uv_) umax_ = std::max(umax_, u);
}

double PoissonTileGenerator::tile_size(double density) const {
  if (!(density > 0) || !std::isfinite(density))
    throw RequestError("density", fmt::format("`density` must be positive, got {}", density));
  return std::sqrt(double(set_.points) / density);
}

std::uint32_t PoissonTileGenerator::lattice(std::int64_t x, std::int64_t y) const {
  if (period_ > 0) x = ((x % period_) + period_) % period_, y = ((y % period_) + period_) % period_;
  return hash_.colour(x, y);
}

// thesis sec. 3.3.2.3: a Wang edge colour is the hash at the edge's midpoint on the lattice of
// half-integers (doubled coordinates): (2x+1, 2y) for edge (x,y)-(x+1,y), (2x, 2y+1) for (x,y)-(x,y+1).
std::uint32_t PoissonTileGenerator::edge(const ColourHash& h, std::int64_t mx, std::int64_t my) const {
  if (period_ > 0) {
    const std::int64_t p = 2 * period_;
    mx = ((mx % p) + p) % p, my = ((my % p) + p) % p;
  }
  return h.colour(mx, my);
}

std::uint64_t PoissonTileGenerator::tile_index(std::int64_t tx, std::int64_t ty) const {
  if (set_.method == PoissonTileMethod::Wang) {
    const auto H = [&](std::int64_t x, std::int64_t y) { return edge(hash_, 2 * x + 1, 2 * y); };
    const auto V = [&](std::int64_t x, std::int64_t y) { return edge(hash_, 2 * x, 2 * y + 1); };
    const std::int64_t x = tx, y = ty;
    const std::uint32_t k[12] = {H(x, y),         V(x + 1, y),     H(x, y + 1),     V(x, y),
                                 V(x, y - 1),     H(x - 1, y),     V(x + 1, y - 1), H(x + 1, y),
                                 V(x + 1, y + 1), H(x + 1, y + 1), V(x, y + 1),     H(x - 1, y + 1)};
    return wang_pd_tile_index(k, set_.colours);
  }
  const std::uint32_t l = set_.lattice_colours();
  const std::uint64_t t =
      parts::corner_tile_index(lattice(tx, ty), lattice(tx + 1, ty), lattice(tx, ty + 1), lattice(tx + 1, ty + 1), l);
  if (!edge_hash_) return t;
  const std::uint32_t ec = set_.edge_colours;
  const std::uint32_t n = edge(*edge_hash_, 2 * tx + 1, 2 * ty), e = edge(*edge_hash_, 2 * tx + 2, 2 * ty + 1),
                      s = edge(*edge_hash_, 2 * tx + 1, 2 * ty + 2), w = edge(*edge_hash_, 2 * tx, 2 * ty + 1);
  return t + std::uint64_t(l) * l * l * l * (((std::uint64_t(n) * ec + e) * ec + s) * ec + w);
}

void PoissonTileGenerator::row_indices(std::int64_t ty, std::int64_t tx0, std::int64_t cols, Scratch& sc) const {
  if (set_.method == PoissonTileMethod::Wang || period_ > 0) {
    sc.wide.resize(std::size_t(cols));
    for (std::int64_t i = 0; i < cols; ++i) sc.wide[std::size_t(i)] = tile_index(tx0 + i, ty);
    return;
  }
  // The fast path of the direct corner tiling: each lattice point hashed once per row pair, and
  // the edge colours along the row by the hash's row evaluation on the doubled lattice.
  const std::size_t n = std::size_t(cols);
  sc.idx.resize(n);
  fill_lattice_corner_tiles(hash_, tx0, ty, 1, int(cols), sc.idx.data());
  sc.wide.assign(sc.idx.begin(), sc.idx.end());
  if (!edge_hash_) return;
  const ColourHash& h = *edge_hash_;
  if (sc.h.n != n || sc.h.x0 != 2 * tx0 + 1) h.prepare(sc.h, 2 * tx0 + 1, n, 2);
  if (sc.v.n != n + 1 || sc.v.x0 != 2 * tx0) h.prepare(sc.v, 2 * tx0, n + 1, 2);
  sc.north.resize(n), sc.south.resize(n), sc.west.resize(n + 1);
  h.row(sc.h, 2 * ty, sc.north.data());
  h.row(sc.h, 2 * ty + 2, sc.south.data());
  h.row(sc.v, 2 * ty + 1, sc.west.data());
  const std::uint64_t ec = set_.edge_colours, l = set_.lattice_colours(), l4 = l * l * l * l;
  for (std::size_t i = 0; i < n; ++i)
    sc.wide[i] += l4 * (((sc.north[i] * ec + sc.west[i + 1]) * ec + sc.south[i]) * ec + sc.west[i]);
}

namespace {
constexpr std::uint32_t kChunk = 128;  // points written per resize()
}  // namespace

void PoissonTileGenerator::row(std::int64_t ty, std::int64_t tx0, std::int64_t tx1, const Window& w, double s,
                               Scratch& sc, std::vector<double>& out) const {
  const std::int64_t cols = tx1 - tx0 + 1;
  row_indices(ty, tx0, cols, sc);
  const double by = double(ty) * s;
  // A tile whose corner plus the largest fl(u s) stays inside needs no test: every point is
  // fl(corner + fl(u s)), monotone in u (and u >= 0).
  const double span = umax_ * s;
  const bool row_inside = by >= w.y0 && by + span < w.y1;
  const double* uv = uv_.data();
  for (std::int64_t i = 0; i < cols; ++i) {
    const std::uint64_t t = sc.wide[std::size_t(i)];
    const std::uint32_t b = offset_[t], e = offset_[t + 1];
    const double bx = double(tx0 + i) * s;
    if (row_inside && bx >= w.x0 && bx + span < w.x1) {
      // In chunks of 2 KiB: resize() writes zeros first, and over a whole tile of 1024 points
      // those zeros would leave the L1 cache before the points overwrite them.
      for (std::uint32_t c = b; c < e; c += kChunk) {
        const std::uint32_t n = std::min(kChunk, e - c);
        const std::size_t at = out.size();
        out.resize(at + 2 * std::size_t(n));
        double* o = out.data() + at;
        const double* q = uv + 2 * std::size_t(c);
        for (std::uint32_t k = 0; k < 2 * n; k += 2) {
          o[k] = bx + q[k] * s;
          o[k + 1] = by + q[k + 1] * s;
        }
      }
    } else {  // a tile across the window's border: every point written, kept when inside
      const std::size_t at = out.size();
      out.resize(at + 2 * std::size_t(e - b));
      double* o = out.data() + at;
      const double* q = uv + 2 * std::size_t(b);
      std::size_t kept = 0;
      for (std::uint32_t k = 0; k < 2 * (e - b); k += 2) {
        const double x = bx + q[k] * s, y = by + q[k + 1] * s;
        o[2 * kept] = x;
        o[2 * kept + 1] = y;
        kept += (x >= w.x0) & (x < w.x1) & (y >= w.y0) & (y < w.y1);
      }
      out.resize(at + 2 * kept);
    }
  }
}

std::vector<double> PoissonTileGenerator::generate(const Window& w, double density, int threads,
                                                  ProgressReporter* progress) const {
  std::vector<double> out;
  generate_into(out, w, density, threads, progress);
  return out;
}

PoissonTileGenerator::Rows PoissonTileGenerator::rows_of(const Window& w, double density) const {
  const double s = tile_size(density);
  return {s, std::int64_t(std::floor(w.x0 / s)), std::int64_t(std::floor(w.x1 / s)), std::int64_t(std::floor(w.y0 / s)),
          std::int64_t(std::floor(w.y1 / s))};
}

void PoissonTileGenerator::generate_into(std::vector<double>& out, const Window& w, double density, int threads,
                                         ProgressReporter* progress) const {
  const Rows r = rows_of(w, density);
  const double s = r.side, tiles_x = double(r.tx1 - r.tx0 + 1), tiles_y = double(r.ty1 - r.ty0 + 1);
  if (!(tiles_x * tiles_y * set_.points < 4e9))
    throw InputError(
        fmt::format("the window holds about {:.3g} points: at most 2^31 per call", tiles_x * tiles_y * set_.points));
  const std::int64_t tx0 = r.tx0, tx1 = r.tx1, ty0 = r.ty0, ty1 = r.ty1;
  const std::int64_t rows = ty1 - ty0 + 1;
  if (progress) progress->set_total(double(rows));
  out.clear();
  if (threads <= 1 || rows < 2) {
    const std::size_t want =
        std::size_t(2 * (w.area() * density * 1.02 + double(set_.points) * (tiles_x + tiles_y) * 2));
    if (want > out.capacity()) {
      out = std::vector<double>();  // no copy of the old contents
      out.reserve(want);
      advise_huge_pages(out.data(), want * sizeof(double));
    }
    Scratch sc;
    for (std::int64_t ty = ty0; ty <= ty1; ++ty) {
      throw_if_interrupted();  // a caught signal ends a long window (base/signals.hpp)
      row(ty, tx0, tx1, w, s, sc, out);
      if (progress) progress->add(1);
    }
    return;
  }
  std::vector<std::vector<double>> rows_out(static_cast<std::size_t>(rows));
  parallel_for(rows, threads, [&](std::int64_t r) {
    throw_if_interrupted();
    thread_local Scratch sc;
    row(ty0 + r, tx0, tx1, w, s, sc, rows_out[std::size_t(r)]);
    if (progress) progress->add(1);
  });
  std::size_t total = 0;
  for (const auto& p : rows_out) total += p.size();
  if (total > out.capacity()) {
    out = std::vector<double>();
    out.reserve(total);
    advise_huge_pages(out.data(), total * sizeof(double));
  }
  out.resize(total);
  std::vector<std::size_t> at(rows_out.size() + 1, 0);
  for (std::size_t i = 0; i < rows_out.size(); ++i) at[i + 1] = at[i] + rows_out[i].size();
  parallel_for(rows, threads, [&](std::int64_t r) {
    std::copy(rows_out[std::size_t(r)].begin(), rows_out[std::size_t(r)].end(),
              out.begin() + std::ptrdiff_t(at[std::size_t(r)]));
  });
}

void PoissonTileGenerator::generate_rows(const Window& w, double density,
                                         const std::function<void(const std::vector<double>&)>& sink, int threads,
                                         ProgressReporter* progress) const {
  const Rows r = rows_of(w, density);
  const std::int64_t rows = r.ty1 - r.ty0 + 1;
  if (progress) progress->set_total(double(rows));
  const std::int64_t batch = threads <= 1 ? 1 : 4 * std::int64_t(threads);
  std::vector<std::vector<double>> out(static_cast<std::size_t>(batch));
  Scratch one;
  for (std::int64_t first = 0; first < rows; first += batch) {
    throw_if_interrupted();  // the sink's file is then removed as the exception unwinds
    const std::int64_t n = std::min(batch, rows - first);
    for (std::int64_t i = 0; i < n; ++i) out[std::size_t(i)].clear();
    if (n == 1) {
      row(r.ty0 + first, r.tx0, r.tx1, w, r.side, one, out[0]);
    } else {
      parallel_for(n, threads, [&](std::int64_t i) {
        thread_local Scratch sc;
        row(r.ty0 + first + i, r.tx0, r.tx1, w, r.side, sc, out[std::size_t(i)]);
      });
    }
    for (std::int64_t i = 0; i < n; ++i) {
      sink(out[std::size_t(i)]);
      if (progress) progress->add(1);
    }
  }
}

}  // namespace tilekit::points
