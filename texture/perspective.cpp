// Perspective rectification of a photographed periodic exemplar (texture/perspective.hpp).
//
// Along one axis ("along": x for lines x = const) the picture is cut into strips 32 px wide
// across the lines; each strip's mean luminance profile, band-passed, has a peak at every line it
// crosses (the polarity, bright or dark mortar, is the sign of the profiles' skew: thin lines are
// the tail). A line through the picture is then a set of crossings (along, across), and the pencil
// of lines through a vanishing point, equally spaced on the wall, is
//   K(u, v) = (g0 u + g1 v + g2) / (g3 u + g4 v + 1)   (K: the line's index, u, v normalised)
// with one line per integer K (Hartley & Zisserman 2004, sec. 2.7: the denominator is the
// vanishing line). Given the indices, K k-weighted is linear in g (g0 u + g1 v + g2 - k g3 u -
// k g4 v = k): least squares. The indices come from growing the fit strip by strip outward from
// the middle one (round K of the fit so far), then re-assigned twice over all strips.
#include "texture/perspective.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

namespace tilekit {

std::array<double, 2> Homography::apply(double x, double y) const {
  const double w = m[6] * x + m[7] * y + m[8];
  return {(m[0] * x + m[1] * y + m[2]) / w, (m[3] * x + m[4] * y + m[5]) / w};
}

Homography Homography::inverse() const {
  const auto& a = m;
  const double c00 = a[4] * a[8] - a[5] * a[7], c01 = a[5] * a[6] - a[3] * a[8], c02 = a[3] * a[7] - a[4] * a[6];
  const double det = a[0] * c00 + a[1] * c01 + a[2] * c02;
  Homography h;
  h.m = {c00 / det, (a[2] * a[7] - a[1] * a[8]) / det, (a[1] * a[5] - a[2] * a[4]) / det,
         c01 / det, (a[0] * a[8] - a[2] * a[6]) / det, (a[2] * a[3] - a[0] * a[5]) / det,
         c02 / det, (a[1] * a[6] - a[0] * a[7]) / det, (a[0] * a[4] - a[1] * a[3]) / det};
  return h;
}

namespace {

constexpr int kStrip = 32;  // strip width across the lines; strips overlap by half

std::vector<double> gaussian_smooth(const std::vector<double>& p, double sigma) {
  const int r = int(std::ceil(3 * sigma)), n = int(p.size());
  std::vector<double> k(std::size_t(2 * r + 1));
  for (int i = -r; i <= r; ++i) k[std::size_t(i + r)] = std::exp(-0.5 * i * i / (sigma * sigma));
  std::vector<double> out(p.size());
  for (int i = 0; i < n; ++i) {
    double s = 0, ws = 0;
    for (int j = -r; j <= r; ++j) {
      const int q = std::clamp(i + j, 0, n - 1);
      s += k[std::size_t(j + r)] * p[std::size_t(q)];
      ws += k[std::size_t(j + r)];
    }
    out[std::size_t(i)] = s / ws;
  }
  return out;
}

// Solves the n x n system a x = b (row-major a) by Gaussian elimination with partial pivoting;
// false when it is singular.
bool solve_linear(std::vector<double> a, std::vector<double> b, std::vector<double>& x) {
  const std::size_t n = b.size();
  for (std::size_t c = 0; c < n; ++c) {
    std::size_t piv = c;
    for (std::size_t r = c + 1; r < n; ++r)
      if (std::abs(a[r * n + c]) > std::abs(a[piv * n + c])) piv = r;
    if (std::abs(a[piv * n + c]) < 1e-12) return false;
    for (std::size_t k = 0; k < n; ++k) std::swap(a[c * n + k], a[piv * n + k]);
    std::swap(b[c], b[piv]);
    for (std::size_t r = c + 1; r < n; ++r) {
      const double f = a[r * n + c] / a[c * n + c];
      for (std::size_t k = c; k < n; ++k) a[r * n + k] -= f * a[c * n + k];
      b[r] -= f * b[c];
    }
  }
  x.assign(n, 0);
  for (std::size_t c = n; c-- > 0;) {
    double s = b[c];
    for (std::size_t k = c + 1; k < n; ++k) s -= a[c * n + k] * x[k];
    x[c] = s / a[c * n + c];
  }
  return true;
}

struct Crossing {
  double u, v;  // normalised (along, across)
  int strip;
};

// The pencil K(u, v) (g0..g4; `params` 2: g0, g2; 3: + g1; 5: all) fitted to crossings with
// line indices k by least squares. False when the system is singular.
bool fit_pencil(const std::vector<Crossing>& c, const std::vector<double>& k, int params, std::array<double, 5>& g) {
  // columns: u, v, 1, -k u, -k v (the first `params` of the order g0, g2, g1, g3, g4)
  static constexpr int order[5] = {0, 2, 1, 3, 4};
  const std::size_t n = std::size_t(params);
  std::vector<double> ata(n * n, 0), atb(n, 0);
  for (std::size_t i = 0; i < c.size(); ++i) {
    const double col[5] = {c[i].u, c[i].v, 1, -k[i] * c[i].u, -k[i] * c[i].v};
    double row[5];
    for (std::size_t j = 0; j < n; ++j) row[j] = col[order[j]];
    for (std::size_t r = 0; r < n; ++r) {
      atb[r] += row[r] * k[i];
      for (std::size_t q = 0; q < n; ++q) ata[r * n + q] += row[r] * row[q];
    }
  }
  std::vector<double> x;
  if (!solve_linear(ata, atb, x)) return false;
  g = {0, 0, 0, 0, 0};
  for (std::size_t j = 0; j < n; ++j) g[std::size_t(order[j])] = x[j];
  return true;
}

double pencil(const std::array<double, 5>& g, double u, double v) {
  return (g[0] * u + g[1] * v + g[2]) / (g[3] * u + g[4] * v + 1);
}

struct AxisFit {
  bool ok = false;
  int lines = 0, points = 0;
  double rms = 1e9, drift = 0, spread = 1;
  std::array<double, 5> g{};
  double sc = 1, along_extent = 0, across_extent = 0;
};

// The crossings of the lines with each strip across the axis (to a fraction of a pixel), and the
// strips' centres; no strips when the picture has too few or no contrast.
struct StripCrossings {
  std::vector<std::vector<double>> peaks;
  std::vector<double> centre;
};

StripCrossings strip_crossings(const Exemplar& e, int axis, int A, int B) {
  StripCrossings out;
  auto lum = [&](int a, int b) { return double(axis == 0 ? luma(e.at(a, b)) : luma(e.at(b, a))); };
  // 1. Band-passed profiles of the strips, and their polarity.
  std::vector<std::vector<double>> prof;
  double m3 = 0, m2 = 0;
  for (int b0 = 0; b0 + kStrip <= B; b0 += kStrip / 2) {
    std::vector<double> p(std::size_t(A), 0);
    for (int b = b0; b < b0 + kStrip; ++b)
      for (int a = 0; a < A; ++a) p[std::size_t(a)] += lum(a, b) / kStrip;
    const std::vector<double> fine = gaussian_smooth(p, 1.5), coarse = gaussian_smooth(p, 12);
    for (int a = 0; a < A; ++a) {
      p[std::size_t(a)] = fine[std::size_t(a)] - coarse[std::size_t(a)];
      m2 += p[std::size_t(a)] * p[std::size_t(a)];
      m3 += p[std::size_t(a)] * p[std::size_t(a)] * p[std::size_t(a)];
    }
    prof.push_back(std::move(p));
    out.centre.push_back(b0 + kStrip / 2.0);
  }
  if (prof.size() < 3 || m2 <= 0) return {};
  const double polarity = m3 >= 0 ? 1 : -1;
  // 2. The crossings: peaks above one standard deviation, to a fraction of a pixel.
  std::vector<std::vector<double>>& peaks = out.peaks;
  peaks.resize(prof.size());
  for (std::size_t s = 0; s < prof.size(); ++s) {
    std::vector<double>& p = prof[s];
    double var = 0;
    for (double& v : p) v *= polarity, var += v * v;
    const double sd = std::sqrt(var / double(A));
    for (int a = 3; a + 3 < A; ++a) {
      const double v = p[std::size_t(a)];
      if (v <= sd) continue;
      bool top = true;
      for (int d = -3; d <= 3 && top; ++d) top = d == 0 || p[std::size_t(a + d)] <= v;
      if (!top) continue;
      const double l = p[std::size_t(a - 1)], r = p[std::size_t(a + 1)], den = l - 2 * v + r;
      peaks[s].push_back(a + 0.5 + (den < 0 ? 0.5 * (l - r) / den : 0));
    }
  }
  return out;
}

AxisFit fit_axis(const Exemplar& e, int axis) {
  AxisFit f;
  const int w = e.width(), h = e.height();
  const int A = axis == 0 ? w : h, B = axis == 0 ? h : w;
  f.along_extent = A, f.across_extent = B;
  f.sc = std::max(A, B) / 2.0;
  // 1-2. The crossings of the lines with band-passed strip profiles.
  StripCrossings crossings = strip_crossings(e, axis, A, B);
  if (crossings.peaks.empty()) return f;
  const std::vector<std::vector<double>>& peaks = crossings.peaks;
  const std::vector<double>& centre = crossings.centre;
  // the strip nearest the middle with three or more crossings, its period and its line nearest
  // the middle
  std::vector<std::size_t> order(peaks.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return std::abs(centre[a] - B / 2.0) < std::abs(centre[b] - B / 2.0);
  });
  std::size_t first = peaks.size();
  double period = 0;
  for (std::size_t s : order) {
    if (peaks[s].size() < 3) continue;
    std::vector<double> gaps;
    for (std::size_t i = 1; i < peaks[s].size(); ++i) gaps.push_back(peaks[s][i] - peaks[s][i - 1]);
    std::vector<double> sorted = gaps;
    std::nth_element(sorted.begin(), sorted.begin() + std::ptrdiff_t(sorted.size() / 2), sorted.end());
    const double m0 = sorted[sorted.size() / 2];
    std::vector<double> kept;
    for (double g : gaps)
      if (g >= 0.6 * m0 && g <= 1.6 * m0) kept.push_back(g);
    if (kept.size() < 2) continue;
    std::nth_element(kept.begin(), kept.begin() + std::ptrdiff_t(kept.size() / 2), kept.end());
    first = s, period = kept[kept.size() / 2];
    break;
  }
  if (first == peaks.size() || period < 4) return f;
  const double sc = f.sc;
  auto norm_u = [&](double a) { return (a - A / 2.0) / sc; };
  auto norm_v = [&](double b) { return (b - B / 2.0) / sc; };
  double anchor = peaks[first][0];
  for (double a : peaks[first])
    if (std::abs(a - A / 2.0) < std::abs(anchor - A / 2.0)) anchor = a;
  std::array<double, 5> g{sc / period, 0, -norm_u(anchor) * sc / period, 0, 0};
  // 3. Grow the fit strip by strip outward from the middle, then re-assign over all strips.
  std::vector<Crossing> cross;
  std::vector<double> k;
  auto assign = [&](std::size_t s, double tolerance) {
    for (double a : peaks[s]) {
      const Crossing c{norm_u(a), norm_v(centre[s]), int(s)};
      const double K = pencil(g, c.u, c.v), ki = std::round(K);
      if (std::abs(K - ki) < tolerance) cross.push_back(c), k.push_back(ki);
    }
  };
  int used = 0;
  for (std::size_t s : order) {
    assign(s, 0.3);
    ++used;
    const int params = used < 2 ? 2 : used < 4 ? 3 : 5;
    if (!cross.empty() && !fit_pencil(cross, k, params, g)) return f;
  }
  for (double tolerance : {0.3, 0.2, 0.2}) {
    cross.clear(), k.clear();
    for (std::size_t s = 0; s < peaks.size(); ++s) assign(s, tolerance);
    if (cross.size() < 8 || !fit_pencil(cross, k, 5, g)) return f;
  }
  // 4. How well it fits, and how far a single period and slant (the affine fit) would miss.
  double sq = 0;
  for (std::size_t i = 0; i < cross.size(); ++i) sq += std::pow(pencil(g, cross[i].u, cross[i].v) - k[i], 2);
  f.rms = std::sqrt(sq / double(cross.size()));
  f.points = int(cross.size());
  std::vector<double> distinct = k;
  std::sort(distinct.begin(), distinct.end());
  f.lines = int(std::unique(distinct.begin(), distinct.end()) - distinct.begin());
  std::array<double, 5> affine{};
  if (!fit_pencil(cross, k, 3, affine)) return f;
  const double cu[2] = {norm_u(0), norm_u(A)}, cv[2] = {norm_v(0), norm_v(B)};
  double lo = 1e300, hi = 0;
  for (double u : cu)
    for (double v : cv) {
      const double den = g[3] * u + g[4] * v + 1;
      if (den < 0.2) return f;  // the vanishing line too near the picture: not a wall seen whole
      f.drift = std::max(f.drift, std::abs(pencil(g, u, v) - pencil(affine, u, v)));
      const double du = 1e-3, slope = (pencil(g, u + du, v) - pencil(g, u - du, v)) / (2 * du);
      lo = std::min(lo, std::abs(slope)), hi = std::max(hi, std::abs(slope));
    }
  f.spread = lo > 0 ? hi / lo : 1;
  f.g = g;
  f.ok = true;
  return f;
}

// The homography of an axis fit: the along coordinate K scaled to one pixel per pixel at the
// picture's centre (minus its value there), the across one v sc / D (the same denominator),
// both in pixels from the centre of the plane.
Homography axis_homography(const AxisFit& f, int axis) {
  const auto& g = f.g;
  const double sc = f.sc, sx = sc / (g[0] - g[2] * g[3]);
  // on normalised (u, v, 1): rows P, Q, D
  const double M[9] = {sx * (g[0] - g[2] * g[3]), sx * (g[1] - g[2] * g[4]), 0, 0, sc, 0, g[3], g[4], 1};
  // (x, y) pixels -> (along, across) pixels -> normalised
  const double N[9] = {1 / sc, 0, -f.along_extent / 2 / sc, 0, 1 / sc, -f.across_extent / 2 / sc, 0, 0, 1};
  double MN[9];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) MN[r * 3 + c] = M[r * 3] * N[c] + M[r * 3 + 1] * N[3 + c] + M[r * 3 + 2] * N[6 + c];
  Homography h;
  if (axis == 0) {
    std::copy(MN, MN + 9, h.m.begin());
  } else {  // swap x and y on both sides
    const int p[3] = {1, 0, 2};
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) h.m[std::size_t(r * 3 + c)] = MN[p[r] * 3 + p[c]];
  }
  return h;
}

}  // namespace

PerspectiveFit fit_perspective(const Exemplar& e) {
  PerspectiveFit out;
  if (e.wrap_w || e.wrap_h) return out;
  AxisFit best;
  int best_axis = -1;
  for (int axis = 0; axis < 2; ++axis) {
    const AxisFit f = fit_axis(e, axis);
    if (!f.ok || f.rms > kPerspectiveMaxRms || f.lines < kPerspectiveMinLines) continue;
    if (best_axis < 0 || f.rms < best.rms) best = f, best_axis = axis;
  }
  if (best_axis < 0) return out;
  out.axis = best_axis;
  out.lines = best.lines;
  out.points = best.points;
  out.rms = best.rms;
  out.drift = best.drift;
  out.spread = best.spread;
  out.to_plane = axis_homography(best, best_axis);
  out.applied = best.drift > kPerspectiveMinDrift;
  return out;
}

Image rectify_image(const Image& img, const PerspectiveFit& fit) {
  if (!fit.applied) return {};
  const int w = img.width, h = img.height;
  // the largest axis-aligned rectangle of the plane inside the picture: the picture's edges
  // mapped to the plane bound it from each side
  double x0 = -1e300, x1 = 1e300, y0 = -1e300, y1 = 1e300;
  constexpr int kSteps = 64;
  for (int i = 0; i <= kSteps; ++i) {
    const double tx = double(w) * i / kSteps, ty = double(h) * i / kSteps;
    x0 = std::max(x0, fit.to_plane.apply(0, ty)[0]);
    x1 = std::min(x1, fit.to_plane.apply(w, ty)[0]);
    y0 = std::max(y0, fit.to_plane.apply(tx, 0)[1]);
    y1 = std::min(y1, fit.to_plane.apply(tx, h)[1]);
  }
  const int ow = int(std::floor(x1 - x0)), oh = int(std::floor(y1 - y0));
  if (ow < kMinExemplarSide || oh < kMinExemplarSide) return {};
  const Homography back = fit.to_plane.inverse();
  Image out(ow, oh, std::vector<std::uint8_t>(std::size_t(ow) * std::size_t(oh) * std::size_t(img.texel_bytes())),
            img.channels);
  out.depth = img.depth;
  for (int y = 0; y < oh; ++y)
    for (int x = 0; x < ow; ++x) {
      const auto p = back.apply(x0 + x + 0.5, y0 + y + 0.5);
      const double fx = std::clamp(p[0] - 0.5, 0.0, w - 1.0), fy = std::clamp(p[1] - 0.5, 0.0, h - 1.0);
      const int xa = std::min(int(fx), w - 2), ya = std::min(int(fy), h - 2);
      const double ax = fx - xa, ay = fy - ya;
      for (int c = 0; c < img.channels; ++c) {
        const double v = (1 - ay) * ((1 - ax) * img.value(xa, ya, c) + ax * img.value(xa + 1, ya, c)) +
                         ay * ((1 - ax) * img.value(xa, ya + 1, c) + ax * img.value(xa + 1, ya + 1, c));
        out.set_value(x, y, c, v);  // rounded and clamped to 0..max at 8 and 16 bits
      }
    }
  return out;
}

Exemplar rectify_exemplar(const Exemplar& e, const PerspectiveFit& fit) {
  Image out = rectify_image(e.image, fit);
  if (out.width == 0) return e;
  return exemplar_from_image(std::move(out), e.name, false);
}

}  // namespace tilekit
