#pragma once
// Point sets to compare the tiles with, made directly in a window:
//  - Bridson's dart throwing ("Fast Poisson disk sampling in arbitrary dimensions", SIGGRAPH
//    2007 sketch): the baseline of the speed and quality benchmarks, plain or toroidal;
//  - white noise (a Poisson distribution, thesis sec. 4.2.1: flat spectrum, rho = 0);
//  - a regular square grid (spikes at multiples of 1 / spacing) and a jittered grid.
// Every set is interleaved (x, y), like the tiled generator's output.
#include <cstdint>
#include <vector>

#include "points/generator.hpp"

namespace tilekit::points {

// Bridson's algorithm with minimum distance `min_distance`: an active list, k = 30 candidates
// per active point drawn uniformly from the annulus [d, 2d), a background grid of cells d / sqrt 2.
// `torus`: distances and candidates wrap around the window (a toroidal set, for spectra).
std::vector<double> bridson_points(const Window& w, double min_distance, std::uint64_t seed, bool torus = false,
                                  int candidates = 30);

// `count` uniform random points.
std::vector<double> white_noise_points(const Window& w, std::uint64_t count, std::uint64_t seed);

// The square grid of spacing 1 / sqrt(density) with a point at the centre of every cell that
// starts inside the window; `jitter` moves each point uniformly within its cell.
std::vector<double> grid_points(const Window& w, double density, bool jitter, std::uint64_t seed);

}  // namespace tilekit::points
