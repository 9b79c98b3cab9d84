#include "tilesets/tiling.hpp"

#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include "base/error.hpp"
#include "base/json_input.hpp"
#include "tilesets/tile_set.hpp"

namespace tilekit {

nlohmann::json tiling_to_json(const Tiling& t) {
  nlohmann::json cells = nlohmann::json::array();
  for (int r = 0; r < t.rows; ++r) {
    nlohmann::json row = nlohmann::json::array();
    for (int c = 0; c < t.cols; ++c) row.push_back(t.at(r, c));
    cells.push_back(std::move(row));
  }
  nlohmann::json j = {{"kind", std::string(kind_name(t.kind))},
                      {"colors", t.colours},
                      {"rows", t.rows},
                      {"cols", t.cols},
                      {"torus", t.torus}};
  if (t.kind == TileKind::Wang && t.cv() != t.ch()) {
    j["horizontal_colors"] = t.ch();
    j["vertical_colors"] = t.cv();
  }
  j["cells"] = std::move(cells);
  return j;
}

Tiling tiling_from_json(const nlohmann::json& doc, const std::string& origin) {
  return tiling_from_json(JsonIn(doc, origin));
}

Tiling tiling_from_json(const JsonIn& j) {
  j.object();
  Tiling t;
  const JsonIn kind = j.at("kind");
  const std::string k = kind.string();
  if (k == "wang") t.kind = TileKind::Wang;
  else if (k == "corner") t.kind = TileKind::Corner;
  else throw kind.error(fmt::format("unknown kind {} (expected \"wang\" or \"corner\")", kind.raw().dump()));
  // Colour counts as in tile sets (tilesets/tile_set.hpp): indices must fit in 32 bits.
  if (j.has("horizontal_colors")) {
    t.colours = std::uint32_t(j.at("horizontal_colors").integer(1, std::int64_t(kMaxWangColourProduct)));
    t.vertical_colours = std::uint32_t(j.at("vertical_colors").integer(1, std::int64_t(kMaxWangColourProduct)));
  } else {
    t.colours = std::uint32_t(j.at("colors").integer(1, std::int64_t(kMaxWangColourProduct)));
  }
  const std::uint64_t product = std::uint64_t(t.ch()) * t.cv();
  if (t.kind == TileKind::Corner ? t.colours > kMaxCornerColours : product > kMaxWangColourProduct)
    throw j.error(fmt::format("{} colours: tile indices (thesis eq. 2.2/2.5) would not fit in 32 bits", product));
  t.rows = int(j.at("rows").integer(1, kMaxTilingSide));
  t.cols = int(j.at("cols").integer(1, kMaxTilingSide));
  if (std::int64_t(t.rows) * t.cols > kMaxTilingCells)
    throw j.error(fmt::format("a {}x{} grid is more than the limit of {} cells", t.rows, t.cols, kMaxTilingCells));
  t.torus = j.at("torus").boolean();
  const JsonIn cells = j.at("cells");
  cells.array(std::size_t(t.rows), std::size_t(t.rows));
  for (int r = 0; r < t.rows; ++r) {
    const JsonIn row = cells[std::size_t(r)];
    row.array(std::size_t(t.cols), std::size_t(t.cols));
    for (int c = 0; c < t.cols; ++c) t.cells.push_back(TileIndex(row[std::size_t(c)].integer(0, 0xffffffffll)));
  }
  return t;
}

Tiling read_tiling_file(const std::string& path) { return tiling_from_json(read_json_file(path, "tiling file"), path); }

}  // namespace tilekit
