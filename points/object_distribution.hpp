#pragma once
// The procedural object distribution function (thesis sec. 7.6.2): a texture basis function
// over the infinite plane that returns, for any (x, y), the closest point of a tiled Poisson
// disk distribution, its distance, whether (x, y) lies in that point's Poisson disk, and a
// unique id of the point (a hash of its tile's coordinates and its index in the tile). The id
// seeds the object placed there: here a class drawn with given probabilities by a seeded hash,
// so every evaluation that touches one object agrees on it, in any window, at any time.
#include <cstdint>
#include <string>
#include <vector>

#include "points/generator.hpp"
#include "image/image.hpp"

namespace tilekit::points {

struct ObjectClass {
  std::string name;
  double probability = 0;
};
// "tree:0.5,rock:0.3,bush:0.2" (probabilities are normalised to sum 1); InputError otherwise.
std::vector<ObjectClass> parse_object_classes(const std::string& text);

class ObjectDistribution {
 public:
  // Objects at `density` per unit area (the scale s of thesis sec. 7.6.2.2).
  ObjectDistribution(const PoissonTileGenerator& gen, double density, std::vector<ObjectClass> classes,
                     std::uint64_t seed);

  struct Evaluation {
    Point2 closest;            // the closest point of the distribution
    double distance = 0;       // to it
    bool inside = false;       // distance < the Poisson disk radius r
    std::uint64_t id = 0;      // unique per point
    std::uint32_t object = 0;  // its class
  };
  // thesis sec. 7.6.2.1: the tile holding (x, y) first; a neighbour tile only when (x, y) is closer
  // to its border than the best distance so far (exact; the thesis bounds this by the largest empty
  // circle), and a candidate closer than r ends the search.
  Evaluation evaluate(double x, double y) const;

  std::uint64_t point_id(std::int64_t tx, std::int64_t ty, std::uint32_t index) const;
  std::uint32_t object_of(std::uint64_t id) const;
  double radius() const { return r_; }
  const std::vector<ObjectClass>& classes() const { return classes_; }

  // Every point of a window with its class: (x, y, class) rows.
  struct Placed {
    double x, y;
    std::uint32_t object;
  };
  std::vector<Placed> scatter(const Window& w) const;
  // The procedural texture of thesis Fig. 7.8: each disk coloured by its object's class (darker
  // towards the rim), the background grey; `px` pixels across the window's longer side.
  Image texture(const Window& w, int px) const;

 private:
  const PoissonTileGenerator& gen_;
  double density_, s_, r_;
  std::vector<ObjectClass> classes_;
  std::vector<double> cumulative_;
  std::uint64_t seed_;
};

}  // namespace tilekit::points
