#pragma once
// The sampling test of thesis sec. 6.2.3: the zone plate f(x, y) = (1 + sin(x^2 + y^2)) / 2 over
// [0, 48]^2, sampled at the points of a set (its window mapped onto the square) and reconstructed
// at 512 x 512 pixels with a Mitchell filter 4 x 4 pixels wide (Mitchell and Netravali 1988,
// B = C = 1/3). 262,144 points make one sample per pixel. The origin is at the lower left.
#include <vector>

#include "points/generator.hpp"
#include "image/image.hpp"

namespace tilekit::points {

struct ZonePlate {
  Image image;
  // RMS difference from f at the pixel centres inside radius 12 (frequencies below 0.7 of the
  // pixel Nyquist frequency: what a sampler should reproduce) and beyond radius 24 (where every
  // sampler aliases; noise and structure both count).
  double rms_inner = 0, rms_outer = 0;
};

ZonePlate zone_plate(const std::vector<double>& xy, const Window& w, int resolution = 512, double extent = 48);

}  // namespace tilekit::points
