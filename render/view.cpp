#include "render/view.hpp"

#include <fmt/format.h>

#include "base/error.hpp"

namespace tilekit {

namespace {

// (tile, fraction in kFracBits) of a coordinate in tiles.
std::pair<std::int32_t, std::uint32_t> fixed(double v) {
  double tile = std::floor(v);
  double frac = std::round((v - tile) * kFracOne);
  if (frac >= kFracOne) tile += 1, frac = 0;
  return {std::int32_t(tile), std::uint32_t(frac)};
}

}  // namespace

ViewRows view_rows(const View& v, int tile_px) {
  if (v.width < 1 || v.height < 1 || v.width > kMaxViewSide || v.height > kMaxViewSide)
    throw RequestError("size",
                       fmt::format("`size` {}x{}: width and height must be 1..{}", v.width, v.height, kMaxViewSide));
  if (!std::isfinite(v.scale) || v.scale <= 0)
    throw RequestError("scale", fmt::format("`scale` must be positive, got {}", v.scale));
  if (!std::isfinite(v.tilt) || v.tilt < 0 || v.tilt > 100)
    throw RequestError("tilt", fmt::format("`tilt` must be 0..100, got {}", v.tilt));
  if (!std::isfinite(v.origin_u) || !std::isfinite(v.origin_v)) throw RequestError("origin", "`origin` must be finite");
  const double s = v.scale / tile_px, W = v.width, H = v.height, t = v.tilt;
  const double u0 = v.origin_u / tile_px, v0 = v.origin_v / tile_px;
  ViewRows out;
  out.dudy_step = float(-s * t / H);
  for (int j = 0; j < v.height; ++j) {
    const double yc = j + 0.5, q = 1 + t * (1 - yc / H);
    // u(x) = centre column + (x + 0.5 - W/2) s q; v(y) = v0 + s G(y) with G' = q^2 (perspective:
    // a row that is q times farther covers q times more texels across and q^2 times more along).
    const double step = s * q, first = u0 + W / 2 * s + (0.5 - W / 2) * step;
    // (1 + t)^3 as products: the preview page (render/preview.cpp) repeats these double operations in
    // JavaScript, whose Math.pow need not round as std::pow does.
    const double vv = v0 + s * (t == 0 ? yc : H / (3 * t) * ((1 + t) * (1 + t) * (1 + t) - q * q * q));
    if (step * kFracOne >= double(2 * kFracOne))
      throw RequestError("scale",
                         fmt::format("`scale` {} (x{:.2f} at the top of the tilted view) moves 2 or more tiles per "
                                     "pixel; use a smaller scale or larger tiles",
                                     v.scale, q));
    const double last = first + (W - 1) * step;
    if (std::abs(first) > 1e9 || std::abs(last) > 1e9 || std::abs(vv) > 1e9)
      throw InputError("the view reaches beyond 10^9 tiles from the origin");
    ViewRow r;
    std::tie(r.tile_u0, r.frac_u0) = fixed(first);
    r.step_u = std::uint32_t(std::round(step * kFracOne));
    std::tie(r.tile_v, r.frac_v) = fixed(vv);
    r.dudx = float(step);
    r.dvdy = float(s * q * q);
    r.dudy0 = float((0.5 - W / 2) * -s * t / H);
    out.rows.push_back(r);
  }
  return out;
}

}  // namespace tilekit
