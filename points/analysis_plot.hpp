#pragma once
// Pictures of the analysis (thesis sec. 6.2): point sets, power spectra (log tone-mapped, DC
// at the centre), the radially averaged power spectrum and the anisotropy of several methods
// side by side (PNG through image/, or SVG text).
#include <string>
#include <vector>

#include "points/analysis_spectrum.hpp"
#include "points/generator.hpp"
#include "image/image.hpp"

namespace tilekit::points {

struct PlotSeries {
  std::string name;
  RadialStats radial;
  double principal_frequency = 0;  // the x axis is frequency / f_p
};

// Two panels, one above the other: radial power (0..3) and anisotropy (-20..+10 dB, with the
// -10 dB background of K = 10 marked), x from 0 to `max_fp` principal frequencies.
Image radial_plot_png(const std::vector<PlotSeries>& series, int width = 640, int height = 520, double max_fp = 2.5);
std::string radial_plot_svg(const std::vector<PlotSeries>& series, int width = 640, int height = 520,
                            double max_fp = 2.5);

// The power spectrum up to `max_fp` principal frequencies each way, grey = 10 log10 P mapped
// from -20 dB (black) to +10 dB (white), as the thesis' spectra are tone-mapped logarithmically.
Image spectrum_image(const PowerSpectrum& s, double max_fp = 2);

// Points as black dots on white, `px` pixels across the window's longer side; `tile_size` > 0
// draws the tile grid in light grey.
Image points_image(const std::vector<double>& xy, const Window& w, int px, double dot_radius, double tile_size = 0);
std::string points_svg(const std::vector<double>& xy, const Window& w, int px, double dot_radius, double tile_size = 0);

}  // namespace tilekit::points
