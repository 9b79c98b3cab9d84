#pragma once
// How a rendered texture surface looks to a person, in numbers: whether it shows the lattice its
// tiles sit on (grid repetition, the power spectrum at the lattice frequencies), whether tile
// borders and sample cuts show (seam ratio, cut visibility), and whether it keeps the exemplar's
// grey levels (histogram distance). Works on any image, with any lattice: square tiles of T
// pixels by default, or two basis vectors (say the triangular lattice of hex-tiling). Each measure
// is defined in texture/README.md.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "image/image.hpp"

namespace tilekit {

// The lattice the content of a surface might repeat on, in pixels: points i*a + j*b + offset.
struct Lattice {
  std::array<double, 2> a{0, 0}, b{0, 0};
  std::array<double, 2> offset{0, 0};  // a lattice point (a tile corner) in image pixels
  static Lattice square(int tile_px) { return {{double(tile_px), 0}, {0, double(tile_px)}, {0, 0}}; }
  // Square and axis-aligned with integer spacing: tile borders are pixel rows and columns.
  bool is_square_grid() const;
  double spacing() const;  // the longer of |a| and |b|
};

struct LagValue {
  int dx = 0, dy = 0;
  double r = 0;  // normalised autocorrelation of luminance
};

struct RadialSpectrum {
  std::vector<double> frequency;  // cycles per pixel, bin centres from 0 to 0.5
  std::vector<double> power;  // mean periodogram of luminance on that ring, relative to white noise of equal variance
  // The spectrum is looked at up to max_frequency: 8 times the lattice's fundamental frequency
  // (the shorter of |a*| and |b*|, the reciprocal basis), at most 0.5.
  double max_frequency = 0.5;
  std::vector<double> lattice_frequencies;  // the harmonics k|a*|, k|b*|, k|a* + b*| up to max_frequency
  // Mean over the reciprocal lattice points i a* + j b* up to max_frequency of 10 log10 (their
  // power / the mean power of their ring): 0 dB when the surface has no lattice.
  double lattice_peak_db = 0;
};

struct TextureAnalysis {
  int width = 0, height = 0;
  Lattice lattice;
  // grid repetition = lattice_correlation - reference_correlation
  double grid_repetition = 0;
  double lattice_correlation = 0;    // mean R at the lattice lags a, b, a+b, 2a, 2b
  double reference_correlation = 0;  // mean |R| at the reference lags (off the lattice)
  std::vector<LagValue> lattice_lags;
  std::size_t reference_lags = 0;
  std::optional<double> seam_ratio;      // square lattices only: step across tile borders / step inside tiles
  std::optional<double> cut_visibility;  // with labels: step across sample boundaries / step inside samples
  // Square lattices: do lines (mortar, plank edges) continue across tile borders as they do
  // inside tiles? line_continuity = border / interior continuity (line_continuity below).
  std::optional<double> line_continuity;
  double border_continuity = 0, interior_continuity = 0;
  std::optional<std::array<double, 3>> histogram_emd;  // with an exemplar: per channel R, G, B, in grey levels
  std::optional<double> histogram_distance;            // their mean
  RadialSpectrum spectrum;
};

// The luminance (Rec. 601 weights) of an RGBA or grey image, row-major.
std::vector<float> luminance(const Image& img);

// Normalised autocorrelation of luminance at integer lag (dx, dy): the mean over the pixel pairs
// inside the image of (L(p) - mean)(L(p + d) - mean), divided by the variance of L.
double autocorrelation(const std::vector<float>& lum, int width, int height, int dx, int dy);

// The reference lags of a lattice: t*v for v in {a, b, a+b}, t from 1/2 to 2 in steps of one
// pixel along v's longer coordinate, rounded to integers, those more than 3 px (in x or in y)
// from every lattice point. For square tiles of T: (d,0), (0,d) and (d,d), T/2 <= d <= 2T, d more
// than 3 px from a multiple of T.
std::vector<std::array<int, 2>> reference_lags(const Lattice& l);

// Per-channel 1-D earth mover's distance between the histograms of two images (R, G, B; grey
// images count as R = G = B): sum over grey levels of |CDF_a - CDF_b|, in grey levels.
std::array<double, 3> histogram_emd(const Image& a, const Image& b);

// Line continuity across the lines x = x0 + k tile (and y = y0 + k tile): per such line, the
// correlation (Pearson, along the line) of the gradient across the line's direction on its two
// sides (|dL/dy| in the columns left and right of a vertical border: horizontal lines continue
// when it matches), averaged over the lines. `interior` takes the lines halfway between.
struct LineContinuity {
  double border = 0, interior = 0, ratio = 0;
};
LineContinuity line_continuity(const Image& img, int tile, int x0 = 0, int y0 = 0);

// Labels: one sample id per pixel as a PNG of the same size (id = R << 16 | G << 8 | B), where
// neighbours with different ids lie on two sides of a cut (texture tiles write them, see
// tile_synthesis.hpp).
std::vector<std::uint32_t> label_ids(const Image& labels);

// InputError for an image too small for the lattice (the lags up to 2 * spacing need an image of
// at least 4 spacings each way), a degenerate lattice, or labels of another size.
TextureAnalysis analyze_texture(const Image& img, const Lattice& l, const Image* exemplar = nullptr,
                                const Image* labels = nullptr, int threads = 1);

// The radially averaged power spectrum, log scale, with the lattice frequencies marked (PNG).
Image spectrum_plot(const TextureAnalysis& a, const std::string& title, int width = 640, int height = 400);

}  // namespace tilekit
