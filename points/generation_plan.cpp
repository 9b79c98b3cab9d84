#include "points/generation_plan.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "base/error.hpp"
#include "base/resources.hpp"
#include "points/point_io.hpp"

namespace tilekit::points {

void require_window_memory(const Window& w, double density, const DensityFunction* fn) {
  // The points (16 bytes each, twice while rows are joined, and the analysis' index) must fit in
  // memory: estimated before any is made. A density function is sampled on a 64 x 64 grid over
  // the window (its largest value, or its own bound where it knows one, times the area).
  double peak = density;
  if (fn) {
    peak = 0;
    for (int j = 0; j < 64; ++j)
      for (int i = 0; i < 64; ++i)
        peak = std::max(peak, (*fn)(w.x0 + (i + 0.5) * w.width() / 64, w.y0 + (j + 0.5) * w.height() / 64));
    peak = std::min(std::max(peak, density), fn->upper_bound(w.x0, w.y0, w.x1, w.y1));
  }
  const double expected = peak * w.area();
  require_memory(expected * 40, fmt::format("a window of about {:.3g} points", expected));
}

// Every point is computed in double precision (a tile's origin plus its offset), whatever file
// it goes to: 53 bits, so a coordinate as large as L is rounded by up to L 2^-53. Far from the
// origin that reaches the points' spacing (a window at 2^53 rounds by 1, and points coincide),
// so a window whose rounding exceeds 1% of the spacing is refused, as float32 files are
// (points/point_io.hpp) with their 24 bits.
void check_double_precision(double largest, double spacing) {
  const double rounding = largest * 0x1p-53;
  if (rounding > 0.01 * spacing)
    throw RequestError("window",
                       fmt::format("`window`: coordinates as large as {:.6g} are computed in double precision, which "
                                   "rounds them by up to {:.3g}, more than 1% of the points' spacing ({:.3g}): the "
                                   "precision limit is coordinates up to {:.3g} at this density; move the window "
                                   "nearer the origin",
                                   largest, rounding, spacing, 0.01 * spacing * 0x1p53));
}

GenerationPlan plan_generation(const GenerationRequest& r, const DensityFunction* fn) {
  const Window& w = r.window;
  if (!(r.density > 0) || !std::isfinite(r.density))
    throw InputError(fmt::format("the density must be positive, got {}", r.density));
  GenerationPlan p;
  p.largest_coordinate = std::max({std::abs(w.x0), std::abs(w.x1), std::abs(w.y0), std::abs(w.y1)});
  p.expected_points = w.area() * r.density;
  check_double_precision(p.largest_coordinate, 1 / std::sqrt(r.density));
  const bool point_file = is_point_file_path(r.out);
  p.stream = r.tile_set && !fn && point_file && !r.analyze;
  // A point file must hold the window's coordinates (at a uniform density; under a density
  // function the points' own spacing is checked when they are written).
  if (point_file && !fn) check_point_file(r.out, p.largest_coordinate, 1 / std::sqrt(r.density));
  if (p.stream) {
    const double per_point = r.out.ends_with(".csv") ? 40 : r.out.ends_with(".f64") ? 16 : 8;
    require_disk(r.out, p.expected_points * per_point,
                 fmt::format("a window of about {:.3g} points", p.expected_points));
  } else {
    require_window_memory(w, r.density, fn);
  }
  return p;
}

}  // namespace tilekit::points
