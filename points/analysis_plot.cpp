#include "points/analysis_plot.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "base/text_escape.hpp"

namespace tilekit::points {

namespace {

constexpr Rgb kPalette[] = {{20, 90, 200}, {210, 50, 40}, {30, 150, 60}, {230, 140, 20}, {130, 60, 170}, {90, 90, 90}};
constexpr Rgb kBlack{0, 0, 0}, kGrid{225, 225, 225}, kBand{242, 242, 250};

std::string hex(Rgb c) {
  return fmt::format("#{:02x}{:02x}{:02x}", c.r, c.g, c.b);
}

// What the radial plot draws, once for PNG and once for SVG.
class Canvas {
 public:
  virtual ~Canvas() = default;
  virtual void line(double x0, double y0, double x1, double y1, Rgb c, int thickness) = 0;
  virtual void rect(double x0, double y0, double x1, double y1, Rgb c) = 0;
  virtual void text(double x, double y, const std::string& s, Rgb c, bool right) = 0;
};

class ImageCanvas : public Canvas {
 public:
  explicit ImageCanvas(Image& img) : img_(img) {}
  void line(double x0, double y0, double x1, double y1, Rgb c, int t) override { img_.line(x0, y0, x1, y1, c, t); }
  void rect(double x0, double y0, double x1, double y1, Rgb c) override {
    img_.rect(int(x0), int(y0), int(x1), int(y1), c);
  }
  void text(double x, double y, const std::string& s, Rgb c, bool right) override {
    img_.text(int(right ? x - Image::text_width(s) : x), int(y - 4), s, c);
  }

 private:
  Image& img_;
};

class SvgCanvas : public Canvas {
 public:
  std::string body;
  void line(double x0, double y0, double x1, double y1, Rgb c, int t) override {
    body += fmt::format(R"(<line x1="{:.1f}" y1="{:.1f}" x2="{:.1f}" y2="{:.1f}" stroke="{}" stroke-width="{}"/>)", x0,
                        y0, x1, y1, hex(c), t);
    body += '\n';
  }
  void rect(double x0, double y0, double x1, double y1, Rgb c) override {
    body += fmt::format(R"(<rect x="{:.1f}" y="{:.1f}" width="{:.1f}" height="{:.1f}" fill="{}"/>)", x0, y0, x1 - x0,
                        y1 - y0, hex(c));
    body += '\n';
  }
  void text(double x, double y, const std::string& s, Rgb c, bool right) override {
    body += fmt::format(R"(<text x="{:.1f}" y="{:.1f}" fill="{}" font-size="11" font-family="sans-serif"{}>{}</text>)",
                        x, y + 4, hex(c), right ? R"( text-anchor="end")" : "", html_escape(s));  // a name: text
    body += '\n';
  }
};

void draw_panel(Canvas& cv, const std::vector<PlotSeries>& series, double x0, double y0, double x1, double y1,
                double max_fp, double lo, double hi, double step, bool anisotropy) {
  const auto X = [&](double f) { return x0 + (x1 - x0) * f / max_fp; };
  const auto Y = [&](double v) { return y1 - (y1 - y0) * (std::clamp(v, lo, hi) - lo) / (hi - lo); };
  if (anisotropy) cv.rect(X(0.5), y0, X(std::min(2.0, max_fp)), y1, kBand);  // the band the summary measures
  for (double f = 0; f <= max_fp + 1e-9; f += 0.5) {
    cv.line(X(f), y0, X(f), y1, kGrid, 1);
    cv.text(X(f), y1 + 12, fmt::format("{:g}", f), kBlack, false);
  }
  for (double v = lo; v <= hi + 1e-9; v += step) {
    cv.line(x0, Y(v), x1, Y(v), kGrid, 1);
    cv.text(x0 - 4, Y(v), fmt::format("{:g}", v), kBlack, true);
  }
  if (anisotropy) cv.line(x0, Y(-10), x1, Y(-10), {150, 150, 150}, 1);  // background noise for K = 10
  cv.line(x0, y0, x0, y1, kBlack, 1);
  cv.line(x0, y1, x1, y1, kBlack, 1);
  for (std::size_t k = 0; k < series.size(); ++k) {
    const auto& s = series[k];
    const Rgb c = kPalette[k % std::size(kPalette)];
    const auto& v = anisotropy ? s.radial.anisotropy_db : s.radial.power;
    for (std::size_t i = 1; i < v.size(); ++i) {
      const double fa = s.radial.frequency[i - 1] / s.principal_frequency,
                   fb = s.radial.frequency[i] / s.principal_frequency;
      if (fb > max_fp) break;
      cv.line(X(fa), Y(v[i - 1]), X(fb), Y(v[i]), c, 1);
    }
  }
}

void draw_radial(Canvas& cv, const std::vector<PlotSeries>& series, int w, int h, double max_fp) {
  const double left = 48, right = w - 16, mid = h / 2.0;
  cv.text(left, 12, "RADIALLY AVERAGED POWER", kBlack, false);
  draw_panel(cv, series, left, 24, right, mid - 24, max_fp, 0, 3, 0.5, false);
  cv.text(left, mid + 4, "ANISOTROPY (DB)", kBlack, false);
  draw_panel(cv, series, left, mid + 16, right, h - 40, max_fp, -20, 10, 5, true);
  cv.text((left + right) / 2, h - 12, "FREQUENCY / PRINCIPAL FREQUENCY", kBlack, false);
  for (std::size_t k = 0; k < series.size(); ++k) {
    const double y = 36 + 14 * double(k);
    cv.line(right - 170, y, right - 150, y, kPalette[k % std::size(kPalette)], 2);
    cv.text(right - 145, y, series[k].name, kBlack, false);
  }
}

}  // namespace

Image radial_plot_png(const std::vector<PlotSeries>& series, int width, int height, double max_fp) {
  Image img(width, height);
  ImageCanvas cv(img);
  draw_radial(cv, series, width, height, max_fp);
  return img;
}

std::string radial_plot_svg(const std::vector<PlotSeries>& series, int width, int height, double max_fp) {
  SvgCanvas cv;
  draw_radial(cv, series, width, height, max_fp);
  return fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{}\" height=\"{}\" viewBox=\"0 0 {} {}\">\n"
      "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n{}</svg>\n",
      width, height, width, height, cv.body);
}

Image spectrum_image(const PowerSpectrum& s, double max_fp) {
  const double fp = principal_frequency(s.density()) * s.side;  // in samples
  const int half = int(std::min<double>(double(s.size / 2) - 1, std::ceil(max_fp * fp)));
  Image img(2 * half + 1, 2 * half + 1);
  for (int ky = -half; ky <= half; ++ky)
    for (int kx = -half; kx <= half; ++kx) {
      const double p = s.at(kx, ky);
      const double db = p > 0 ? 10 * std::log10(p) : -100;
      const auto g = std::uint8_t(std::lround(255 * std::clamp((db + 20) / 30, 0.0, 1.0)));
      img.set(kx + half, ky + half, {g, g, g});
    }
  return img;
}

Image points_image(const std::vector<double>& xy, const Window& w, int px, double dot, double tile_size) {
  const double scale = px / std::max(w.width(), w.height());
  Image img(std::max(1, int(std::lround(w.width() * scale))), std::max(1, int(std::lround(w.height() * scale))));
  if (tile_size > 0) {
    for (double x = std::ceil(w.x0 / tile_size) * tile_size; x < w.x1; x += tile_size)
      img.line((x - w.x0) * scale, 0, (x - w.x0) * scale, img.height, {200, 200, 220});
    for (double y = std::ceil(w.y0 / tile_size) * tile_size; y < w.y1; y += tile_size)
      img.line(0, (y - w.y0) * scale, img.width, (y - w.y0) * scale, {200, 200, 220});
  }
  for (std::size_t i = 0; i + 1 < xy.size(); i += 2)
    img.disc((xy[i] - w.x0) * scale, (xy[i + 1] - w.y0) * scale, dot, kBlack);
  return img;
}

std::string points_svg(const std::vector<double>& xy, const Window& w, int px, double dot, double tile_size) {
  const double scale = px / std::max(w.width(), w.height());
  const double width = w.width() * scale, height = w.height() * scale;
  std::string body;
  if (tile_size > 0) {
    for (double x = std::ceil(w.x0 / tile_size) * tile_size; x < w.x1; x += tile_size)
      body += fmt::format("<line x1=\"{0:.2f}\" y1=\"0\" x2=\"{0:.2f}\" y2=\"{1:.2f}\" stroke=\"#c8c8dc\"/>\n",
                          (x - w.x0) * scale, height);
    for (double y = std::ceil(w.y0 / tile_size) * tile_size; y < w.y1; y += tile_size)
      body += fmt::format("<line x1=\"0\" y1=\"{0:.2f}\" x2=\"{1:.2f}\" y2=\"{0:.2f}\" stroke=\"#c8c8dc\"/>\n",
                          (y - w.y0) * scale, width);
  }
  for (std::size_t i = 0; i + 1 < xy.size(); i += 2)
    body += fmt::format("<circle cx=\"{:.2f}\" cy=\"{:.2f}\" r=\"{:.2f}\"/>\n", (xy[i] - w.x0) * scale,
                        (xy[i + 1] - w.y0) * scale, dot);
  return fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{0:.0f}\" height=\"{1:.0f}\" viewBox=\"0 0 {0:.2f} "
      "{1:.2f}\">\n"
      "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n{2}</svg>\n",
      width, height, body);
}

}  // namespace tilekit::points
