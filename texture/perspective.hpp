#pragma once
// Perspective rectification of a photographed periodic exemplar. A wall photographed at an angle
// is periodic only roughly: its mortar lines converge towards a vanishing point and their spacing
// drifts across the picture (scikit-image's brick: columns 30 px apart at the top, 42 px at the
// bottom), so no single period fits it, and samples from different places of it have bricks of
// different widths and slants that break where they meet. Here the lines that run through the
// whole picture (the bed joints of a wall, whichever way it is laid) are found and a homography
// of the plane (Hartley & Zisserman 2004, sec. 2.7: the vanishing line and the pencil of lines
// through the vanishing point) is fitted that maps them to parallel lines equally spaced; the
// exemplar is resampled through it. The other axis keeps the picture's projective foreshortening
// undone by the same denominator (the rows of a wall then have one length again) but is not
// otherwise fitted: the synthesis resamples each axis to whole periods afterwards.
#include <array>

#include "texture/exemplar.hpp"

namespace tilekit {

// A plane projective map, 3x3 row-major, on homogeneous (x, y, 1).
struct Homography {
  std::array<double, 9> m{1, 0, 0, 0, 1, 0, 0, 0, 1};
  std::array<double, 2> apply(double x, double y) const;
  Homography inverse() const;
};

struct PerspectiveFit {
  bool applied = false;  // the exemplar was resampled (a fit was found and the drift was worth it)
  int axis = -1;         // 0: the fitted lines are x = const (columns), 1: y = const (rows); -1: none
  int lines = 0;         // distinct lines in the fit
  int points = 0;        // line crossings (one per strip and line) in the fit
  double rms = 0;        // residual of the crossings, in periods
  double drift = 0;      // how far the best single period and slant miss the lines, in periods
  double spread = 1;     // largest over smallest line spacing across the picture
  Homography to_plane;   // exemplar pixel (x + 0.5, y + 0.5) -> rectified pixel centre
};

// The fit is used when its crossings lie within this many periods of the fitted lines (rms)...
inline constexpr double kPerspectiveMaxRms = 0.06;
// ...at least this many distinct lines were found...
inline constexpr int kPerspectiveMinLines = 4;
// ...and a single period would miss the lines by more than this many periods somewhere.
inline constexpr double kPerspectiveMinDrift = 0.25;

// Fits the lines of `e` (not for a tileable exemplar, which is periodic by construction: it is
// returned as it came with `applied` false) along each axis and keeps the better fit.
PerspectiveFit fit_perspective(const Exemplar& e);

// The exemplar resampled (bilinear) through fit.to_plane over the largest axis-aligned rectangle
// of the plane that the picture covers; unchanged when !fit.applied.
Exemplar rectify_exemplar(const Exemplar& e, const PerspectiveFit& fit);
// The same resampling of any image of the exemplar's size (any depth and channels): another map
// of the same wall. Empty where rectify_exemplar returns the exemplar as it came.
Image rectify_image(const Image& img, const PerspectiveFit& fit);

}  // namespace tilekit
