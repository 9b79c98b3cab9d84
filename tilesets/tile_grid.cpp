#include "tilesets/tile_grid.hpp"

#include <fmt/format.h>

#include <cassert>
#include <nlohmann/json.hpp>
#include <string_view>

#include "base/error.hpp"
#include "base/json_input.hpp"
#include "tilesets/tile_set.hpp"
#include "tilesets/window_torus.hpp"

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
  if (t.kind == TileKind::Window) j["window"] = {t.window_rows, t.window_cols};
  j["cells"] = std::move(cells);
  return j;
}

namespace {

constexpr std::string_view kPegDigits = "0123456789abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ";

Tiling tiling_from_pegs_json(const Tiling& head, const JsonIn& rows) {
  if (head.kind == TileKind::Wang || !head.torus) throw rows.error("\"pegs\" describes a corner or window torus only");
  if (head.colours > kPegDigits.size())
    throw rows.error(fmt::format("\"pegs\" holds at most {} colours", kPegDigits.size()));
  rows.array(std::size_t(head.rows), std::size_t(head.rows));
  std::vector<Colour> pegs;
  pegs.reserve(std::size_t(head.rows) * std::size_t(head.cols));
  for (int r = 0; r < head.rows; ++r) {
    const JsonIn row = rows[std::size_t(r)];
    const std::string text = row.string(std::size_t(head.cols));
    if (text.size() != std::size_t(head.cols)) throw row.error(fmt::format("expected a string of {} digits", head.cols));
    for (char ch : text) {
      const std::size_t d = kPegDigits.find(ch);
      if (d == std::string_view::npos || d >= head.colours)
        throw row.error(fmt::format("'{}' is not a colour below {}", ch, head.colours));
      pegs.push_back(Colour(d));
    }
  }
  if (head.kind == TileKind::Window)
    return window_torus_from_pegs(pegs, head.rows, head.cols, head.colours, head.window_rows, head.window_cols);
  return corner_torus_from_pegs(pegs, head.rows, head.cols, head.colours);
}

}  // namespace

Tiling corner_torus_from_pegs(const std::vector<Colour>& pegs, int rows, int cols, std::uint32_t colours) {
  assert(pegs.size() == std::size_t(rows) * std::size_t(cols));
  Tiling t(TileKind::Corner, colours, rows, cols, true);
  auto P = [&](int r, int c) { return pegs[std::size_t(r % rows) * std::size_t(cols) + std::size_t(c % cols)]; };
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) {
      CornerTile ct{P(r, c + 1), P(r + 1, c + 1), P(r + 1, c), P(r, c)};  // ne, se, sw, nw
      t.at(r, c) = corner_index(ct, colours);                             // thesis eq. (2.5)
    }
  return t;
}

std::vector<Colour> pegs_of_corner_torus(const Tiling& t) {
  std::vector<Colour> pegs(t.cells.size());
  for (std::size_t i = 0; i < t.cells.size(); ++i) pegs[i] = corner_tile(t.cells[i], t.colours).nw;
  return pegs;
}

nlohmann::json tiling_to_peg_json(const Tiling& t) {
  if (t.kind == TileKind::Wang || !t.torus) throw InputError("the peg form is for corner and window tori only");
  if (t.colours > kPegDigits.size())
    throw InputError(fmt::format("the peg form holds at most {} colours, got {}", kPegDigits.size(), t.colours));
  const bool window = t.kind == TileKind::Window;
  const std::vector<Colour> pegs = window ? pegs_of_window_torus(t) : pegs_of_corner_torus(t);
  const Tiling again = window ? window_torus_from_pegs(pegs, t.rows, t.cols, t.colours, t.window_rows, t.window_cols)
                              : corner_torus_from_pegs(pegs, t.rows, t.cols, t.colours);
  if (again.cells != t.cells)
    throw InputError("neighbouring windows do not match: the tiling is not the window grid of a peg colouring");
  nlohmann::json rows = nlohmann::json::array();
  for (int r = 0; r < t.rows; ++r) {
    std::string row;
    for (int c = 0; c < t.cols; ++c) row += kPegDigits[pegs[std::size_t(r) * std::size_t(t.cols) + std::size_t(c)]];
    rows.push_back(std::move(row));
  }
  nlohmann::json j = {{"kind", std::string(kind_name(t.kind))}, {"colors", t.colours}, {"rows", t.rows},
                      {"cols", t.cols}, {"torus", true}};
  if (window) j["window"] = {t.window_rows, t.window_cols};
  j["pegs"] = std::move(rows);
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
  else if (k == "window") t.kind = TileKind::Window;
  else throw kind.error(fmt::format("unknown kind {} (expected \"wang\", \"corner\" or \"window\")", kind.raw().dump()));
  // Colour counts as in tile sets (tilesets/tile_set.hpp): indices must fit in 32 bits.
  if (j.has("horizontal_colors")) {
    t.colours = std::uint32_t(j.at("horizontal_colors").integer(1, std::int64_t(kMaxWangColourProduct)));
    t.vertical_colours = std::uint32_t(j.at("vertical_colors").integer(1, std::int64_t(kMaxWangColourProduct)));
  } else {
    t.colours = std::uint32_t(j.at("colors").integer(1, std::int64_t(kMaxWangColourProduct)));
  }
  const std::uint64_t product = std::uint64_t(t.ch()) * t.cv();
  if (t.kind == TileKind::Wang ? product > kMaxWangColourProduct : t.colours > kMaxCornerColours)
    throw j.error(fmt::format("{} colours: tile indices (thesis eq. 2.2/2.5) would not fit in 32 bits", product));
  if (t.kind == TileKind::Window) {
    // Window indices (window_torus.hpp) fit 32 bits while there are at most kMaxTiles windows.
    const JsonIn w = j.at("window");
    w.array(2, 2);
    t.window_rows = int(w[0].integer(1, kMaxTilingSide));
    t.window_cols = int(w[1].integer(1, kMaxTilingSide));
    if (window_count(t.colours, t.window_rows, t.window_cols, kMaxTiles) == 0)
      throw w.error(fmt::format("{}x{} windows over {} symbols are more than the limit of {} windows", t.window_rows,
                                t.window_cols, t.colours, kMaxTiles));
  }
  t.rows = int(j.at("rows").integer(1, kMaxTilingSide));
  t.cols = int(j.at("cols").integer(1, kMaxTilingSide));
  if (std::int64_t(t.rows) * t.cols > kMaxTilingCells)
    throw j.error(fmt::format("a {}x{} grid is more than the limit of {} cells", t.rows, t.cols, kMaxTilingCells));
  t.torus = j.at("torus").boolean();
  if (!j.has("cells") && j.has("pegs")) return tiling_from_pegs_json(t, j.at("pegs"));
  const JsonIn cells = j.at("cells");
  cells.array(std::size_t(t.rows), std::size_t(t.rows));
  t.cells.reserve(std::size_t(t.rows) * std::size_t(t.cols));
  for (int r = 0; r < t.rows; ++r) {
    const JsonIn row = cells[std::size_t(r)];
    row.array(std::size_t(t.cols), std::size_t(t.cols));
    for (int c = 0; c < t.cols; ++c) t.cells.push_back(TileIndex(row[std::size_t(c)].integer(0, 0xffffffffll)));
  }
  return t;
}

Tiling read_tiling_file(const std::string& path) { return tiling_from_json(read_json_file(path, "tiling file"), path); }

}  // namespace tilekit
