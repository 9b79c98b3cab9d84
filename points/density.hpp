#pragma once
// Target density functions for non-uniform point sets (points per unit area at (x, y)): a
// constant, an analytic expression in x and y, or a grey-scale image laid over a rectangle
// (dark = dense, as for stippling; Kopf et al. 2006 sec. 6.2).
#include <limits>
#include <memory>
#include <string>

#include "points/generator.hpp"

namespace tilekit::points {

class DensityFunction {
 public:
  virtual ~DensityFunction() = default;
  virtual double operator()(double x, double y) const = 0;
  // A bound on the density over [x0, x1) x [y0, y1) (+infinity when unknown): lets the
  // recursive generator skip tiles that need no more points.
  virtual double upper_bound(double, double, double, double) const { return std::numeric_limits<double>::infinity(); }
  virtual std::string describe() const = 0;
};

std::unique_ptr<DensityFunction> constant_density(double d);

// An expression in x, y (and r = sqrt(x^2 + y^2), pi, e) with + - * / ^, parentheses and the
// functions sin cos tan exp log sqrt abs floor min max pow clamp(v, lo, hi). Negative values
// count as 0; a value that is not finite where it is evaluated (exp(1000), 0/0, log(-1)) is an
// InputError, as is an empty expression. InputError naming the position of a syntax error, e.g.
// "1000 * (exp(-20 * ((x-0.5)^2 + (y-0.5)^2)) + 0.05)" (thesis Fig. 4.44, shifted to [0,1]^2).
std::unique_ptr<DensityFunction> expression_density(const std::string& text);

// A PNG/PGM/JPEG image stretched over `where`: density = max_density * (1 - grey), grey in
// [0, 1] (with `invert`, max_density * grey); 0 outside. Bilinear between pixel centres.
std::unique_ptr<DensityFunction> image_density(const std::string& path, const Window& where, double max_density,
                                               bool invert = false);

}  // namespace tilekit::points
