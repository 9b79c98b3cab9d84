#pragma once
// The one constrained Poisson disk sampler every tile construction uses (thesis ch. 4): place
// `count` new points in the free part of a domain, no two points (new or fixed) closer than a
// minimum distance, by relaxation dart throwing (McCool and Fiume 1992, thesis sec. 4.2.4.2)
// followed by Lloyd's relaxation (thesis sec. 4.2.4.3) that keeps the constraints: fixed
// points never move and new points never leave the free region (displacements that would
// enter it are shortened, thesis sec. 4.3: "clipping the displacement vectors").
//
// Lloyd's relaxation is discrete: each point moves to the centroid of the samples (a regular
// lattice of spacing min_distance / samples_per_distance over the domain) nearest to it, the
// usual sampled estimate of its Voronoi cell's centroid. After `lloyd` iterations (0 by default:
// Lloyd makes sets regular, with a tall spectral peak), pairs still closer than the distance push
// each other apart; a try that does not get there within `repair` such steps starts over from
// new darts ("if the desired Poisson disk radius is not reached, this process is repeated",
// thesis sec. 4.5).
//
// Between the darts and Lloyd, `hard_disk_sweeps` sweeps of hard-disk Monte Carlo move the new
// points at random without ever breaking the distance: dart throwing next to fixed points leaves
// a depleted band along them, in the same place in every tile, which shows as spikes in the
// spectrum of tilings; the sweeps remove it.
//
// A problem may ask for rotational symmetry about a centre (order 2 or 4): points then come in
// orbits of that size, as the self-symmetric rotatable tiles of Li et al. require.
#include <cstdint>
#include <functional>
#include <vector>

#include "points/geometry.hpp"

namespace tilekit::points {

struct SamplingProblem {
  double x0 = 0, y0 = 0, w = 1, h = 1;  // the domain [x0, x0 + w) x [y0, y0 + h)
  bool torus = false;                   // wrap both axes
  std::function<bool(Point2)> free;     // where the new points may lie (empty: the whole domain)
  std::vector<Point2> fixed;            // constraints that never move (may lie outside a plain domain)
  std::size_t count = 0;                // new points to place; a multiple of symmetry_order
  int symmetry_order = 1;               // 1, 2 or 4: invariance under rotations by 360/order degrees
  Point2 centre;                        // about this point
};

struct SamplingOptions {
  double min_distance = 0;           // between any two points, new-new and new-fixed
  int hard_disk_sweeps = 30;         // hard-disk Monte Carlo sweeps after the darts (100 gave the same spectra)
  int lloyd = 0;                     // Lloyd iterations before the push-apart repair
  int repair = 80;                   // push-apart steps before a try starts over
  int tries = 24;                    // tries before giving up (InputError)
  double samples_per_distance = 10;  // Lloyd sample lattice: min_distance / this apart
};

struct SamplingResult {
  std::vector<Point2> points;  // the new points (wrapped into a torus domain)
  double min_distance = 0;     // the smallest distance involving a new point (up to 2 min_distance)
  int lloyd_iterations = 0;    // in the successful try
  int tries = 0;               // tries used (1 = first)
};

// Throws InputError naming the problem when no try reaches the distance (the relative radius
// asked for is too large for the count) or the free region cannot hold the points.
SamplingResult sample_poisson_disk(const SamplingProblem& problem, const SamplingOptions& options, std::uint64_t seed);

}  // namespace tilekit::points
