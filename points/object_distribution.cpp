#include "points/object_distribution.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>

#include "base/error.hpp"
#include "base/hash.hpp"
#include "base/random.hpp"

namespace tilekit::points {

std::vector<ObjectClass> parse_object_classes(const std::string& text) {
  std::vector<ObjectClass> out;
  double total = 0;
  std::size_t pos = 0;
  while (pos <= text.size()) {
    const std::size_t comma = std::min(text.find(',', pos), text.size());
    const std::string item = text.substr(pos, comma - pos);
    const std::size_t colon = item.find(':');
    double p = 0;
    const auto r = colon == std::string::npos ? std::from_chars_result{nullptr, std::errc::invalid_argument}
                                              : std::from_chars(item.data() + colon + 1, item.data() + item.size(), p);
    if (colon == 0 || colon == std::string::npos || r.ec != std::errc() || r.ptr != item.data() + item.size() ||
        !(p > 0) || !std::isfinite(p))
      throw RequestError(
          "objects",
          fmt::format("`objects`: expected NAME:PROBABILITY,... with positive probabilities, got '{}'", item));
    out.push_back({item.substr(0, colon), p});
    total += p;
    pos = comma + 1;
  }
  // Weights as large as 1e308 sum to infinity: scale by the largest first, then normalise.
  double largest = 0;
  for (const auto& c : out) largest = std::max(largest, c.probability);
  total = 0;
  for (auto& c : out) total += c.probability /= largest;
  for (auto& c : out) c.probability /= total;
  return out;
}

ObjectDistribution::ObjectDistribution(const PoissonTileGenerator& gen, double density,
                                       std::vector<ObjectClass> classes, std::uint64_t seed)
    : gen_(gen),
      density_(density),
      s_(gen.tile_size(density)),
      r_(gen.set().radius * s_),
      classes_(std::move(classes)),
      seed_(seed) {
  if (classes_.empty()) throw RequestError("objects", "`objects` needs at least one class");
  double c = 0;
  for (const auto& k : classes_) cumulative_.push_back(c += k.probability);
  cumulative_.back() = 1;
}

std::uint64_t ObjectDistribution::point_id(std::int64_t tx, std::int64_t ty, std::uint32_t index) const {
  // thesis sec. 7.6.2.1: a combination of the tile coordinates' hash and the point's index.
  return StableHash().add(std::uint64_t(tx)).add(std::uint64_t(ty)).add(index, 4).mixed();
}

std::uint32_t ObjectDistribution::object_of(std::uint64_t id) const {
  SplitMix64 rng(derive_seed(seed_, id));
  const double u = rng.uniform();
  return std::uint32_t(std::upper_bound(cumulative_.begin(), cumulative_.end(), u) - cumulative_.begin());
}

ObjectDistribution::Evaluation ObjectDistribution::evaluate(double x, double y) const {
  const std::int64_t tx = std::int64_t(std::floor(x / s_)), ty = std::int64_t(std::floor(y / s_));
  Evaluation e;
  e.distance = std::numeric_limits<double>::infinity();
  std::int64_t bx = 0, by = 0;
  std::uint32_t bi = 0;
  const auto search = [&](std::int64_t cx, std::int64_t cy) {
    const auto& pts = gen_.set().tiles[gen_.tile_index(cx, cy)];
    for (std::uint32_t i = 0; i < pts.size(); ++i) {
      const double px = (double(cx) + pts[i].x) * s_, py = (double(cy) + pts[i].y) * s_;
      const double d = std::hypot(px - x, py - y);
      if (d < e.distance) e.distance = d, e.closest = {px, py}, bx = cx, by = cy, bi = i;
    }
  };
  search(tx, ty);
  // Distances from (x, y) to the tile's borders decide which neighbours can hold a closer point.
  const double fx = x / s_ - double(tx), fy = y / s_ - double(ty);
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      if ((dx == 0 && dy == 0) || e.distance < r_) continue;  // within r: nothing can be closer
      const double gx = dx < 0 ? fx : dx > 0 ? 1 - fx : 0, gy = dy < 0 ? fy : dy > 0 ? 1 - fy : 0;
      if (std::hypot(gx, gy) * s_ < e.distance) search(tx + dx, ty + dy);
    }
  e.inside = e.distance < r_;
  e.id = point_id(bx, by, bi);
  e.object = object_of(e.id);
  return e;
}

std::vector<ObjectDistribution::Placed> ObjectDistribution::scatter(const Window& w) const {
  std::vector<Placed> out;
  const std::int64_t tx0 = std::int64_t(std::floor(w.x0 / s_)), tx1 = std::int64_t(std::floor(w.x1 / s_));
  const std::int64_t ty0 = std::int64_t(std::floor(w.y0 / s_)), ty1 = std::int64_t(std::floor(w.y1 / s_));
  for (std::int64_t ty = ty0; ty <= ty1; ++ty)
    for (std::int64_t tx = tx0; tx <= tx1; ++tx) {
      const auto& pts = gen_.set().tiles[gen_.tile_index(tx, ty)];
      for (std::uint32_t i = 0; i < pts.size(); ++i) {
        const double x = double(tx) * s_ + pts[i].x * s_, y = double(ty) * s_ + pts[i].y * s_;
        if (x >= w.x0 && x < w.x1 && y >= w.y0 && y < w.y1)
          out.push_back({x, y, object_of(point_id(tx, ty, i))});
      }
    }
  return out;
}

Image ObjectDistribution::texture(const Window& w, int px) const {
  static constexpr Rgb kClass[] = {{46, 125, 50}, {121, 85, 72}, {251, 192, 45}, {30, 136, 229},
                                   {216, 27, 96}, {0, 137, 123}, {94, 53, 177},  {244, 81, 30}};
  const double scale = px / std::max(w.width(), w.height());
  Image img(std::max(1, int(w.width() * scale)), std::max(1, int(w.height() * scale)), Rgb{236, 236, 228});
  for (int j = 0; j < img.height; ++j)
    for (int i = 0; i < img.width; ++i) {
      const Evaluation e = evaluate(w.x0 + (i + 0.5) / scale, w.y0 + (j + 0.5) / scale);
      if (!e.inside) continue;
      const Rgb c = kClass[e.object % std::size(kClass)];
      const double shade = 1 - 0.45 * e.distance / r_;
      img.set(i, j, {std::uint8_t(c.r * shade), std::uint8_t(c.g * shade), std::uint8_t(c.b * shade)});
    }
  return img;
}

}  // namespace tilekit::points
