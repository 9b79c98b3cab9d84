// --impose group specs (solver/impose_group.hpp): parsing, then building the group on a few
// tori, as `pack --impose` does for corner and Wang packings.
#include <cstdint>
#include <string>

#include "base/error.hpp"
#include "solver/impose_group.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace tilekit;
  const std::string text(reinterpret_cast<const char*>(data), size);
  GroupSpec spec;
  try {
    spec = parse_group_spec(text);
  } catch (const InputError&) {
    return 0;
  }
  struct Shape {
    TileKind kind;
    std::uint32_t ch, cv;
    int rows, cols;
    bool packing;
  } shapes[] = {{TileKind::Corner, 4, 4, 16, 16, true}, {TileKind::Wang, 2, 2, 4, 4, true},
                {TileKind::Wang, 2, 3, 6, 6, true},    {TileKind::Corner, 3, 3, 6, 5, false}};
  for (const Shape& s : shapes) {
    try {
      const ImposedGroup g = ImposedGroup::build(spec, s.kind, s.ch, s.cv, s.rows, s.cols, s.packing);
      g.spec_text();
      g.to_json().dump();
    } catch (const InputError&) {
    }
  }
  return 0;
}
