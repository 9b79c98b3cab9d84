#pragma once
// How `points generate` makes a window, decided before any point is made: a tile set written to
// a point file (and not analysed) streams row by row, so the disk bounds the window, not the
// memory; everything else is made whole in memory. Each way is checked against its budget up
// front (free disk or memory, base/resources.hpp), and a point file against the precision its
// coordinates need, so that a window that cannot be done is refused before the work, not after.
#include <string>

#include "points/density.hpp"
#include "points/generator.hpp"

namespace tilekit::points {

struct GenerationRequest {
  Window window;
  double density = 0;     // points per unit area (the scale of the base tiles under a function)
  bool tile_set = false;  // the points come from a Poisson tile set (corner, wang, dual)
  std::string out;        // the output path ("" = none)
  bool analyze = false;   // the radius analysis needs the points in memory
};

struct GenerationPlan {
  bool stream = false;            // row by row straight into the point file `out`
  double expected_points = 0;     // area x density
  double largest_coordinate = 0;  // what a point file must hold
};

// The plan, after the checks above; InputError (exit 2) naming the budget that a window exceeds.
GenerationPlan plan_generation(const GenerationRequest& r, const DensityFunction* fn);

// InputError (exit 2, naming the memory limit and TILEKIT_MEMORY) unless the points of `w` at
// `density` (or following `fn`, sampled) fit in memory: every command that makes points calls it
// before any work.
void require_window_memory(const Window& w, double density, const DensityFunction* fn);

}  // namespace tilekit::points
