// The small languages of the command line, beyond the flags fuzz_flags covers: density
// expressions (`--density-expr`, evaluated at a few points: any value, never a crash or a
// stack overflow), object classes (`--objects NAME:P,...`: probabilities that sum to 1), windows
// (`--window x0,y0,x1,y1`: finite and ordered), colour-quotient lifts (`--lift`), and the names
// of methods and hashes. Byte 0 picks the parser; the rest is the text.
#include <cmath>
#include <cstdint>
#include <string>

#include "base/error.hpp"
#include "points/density.hpp"
#include "points/generator.hpp"
#include "points/object_distribution.hpp"
#include "points/poisson_tiles.hpp"
#include "solver/colour_lift_model.hpp"
#include "tiling/lattice_hash.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace tilekit;
  using namespace tilekit::points;
  if (size == 0) return 0;
  const std::string text(reinterpret_cast<const char*>(data) + 1, size - 1);
  try {
    switch (data[0] % 6) {
      case 0: {
        const auto f = expression_density(text);
        for (double x : {-1.0, 0.0, 0.5, 1e6})
          if (const double v = (*f)(x, 0.25); !(v >= 0) || !std::isfinite(v)) __builtin_trap();
        break;
      }
      case 1: {
        double sum = 0;
        for (const ObjectClass& c : parse_object_classes(text)) {
          if (!(c.probability > 0) || c.probability > 1) __builtin_trap();
          sum += c.probability;
        }
        if (std::abs(sum - 1) > 1e-9) __builtin_trap();
        break;
      }
      case 2: {
        const Window w = parse_window(text);
        if (!(w.x0 < w.x1 && w.y0 < w.y1) || !std::isfinite(w.area())) __builtin_trap();
        break;
      }
      case 3: parse_lift_spec(text); break;
      case 4: parse_poisson_tile_method(text); break;
      default: parse_hash_kind(text);
    }
  } catch (const InputError&) {
  }
  return 0;
}
