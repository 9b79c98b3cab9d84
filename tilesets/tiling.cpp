#include "tilesets/tiling.hpp"

#include <fmt/format.h>

#include <cassert>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string_view>

#include "base/error.hpp"

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

namespace {

constexpr std::string_view kPegDigits = "0123456789abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ";

template <class Fail>
Tiling tiling_from_pegs_json(const Tiling& head, const nlohmann::json& rows, const Fail& fail) {
  if (head.kind != TileKind::Corner || !head.torus) throw fail("\"pegs\" describes a corner torus only");
  if (head.colours > kPegDigits.size()) throw fail(fmt::format("\"pegs\" holds at most {} colours", kPegDigits.size()));
  if (!rows.is_array() || rows.size() != std::size_t(head.rows))
    throw fail(fmt::format("\"pegs\" must be an array of {} strings", head.rows));
  std::vector<Colour> pegs;
  pegs.reserve(std::size_t(head.rows) * std::size_t(head.cols));
  for (int r = 0; r < head.rows; ++r) {
    const auto& row = rows[std::size_t(r)];
    if (!row.is_string() || row.get_ref<const std::string&>().size() != std::size_t(head.cols))
      throw fail(fmt::format("row {} of \"pegs\" must be a string of {} digits", r, head.cols));
    for (char ch : row.get_ref<const std::string&>()) {
      const std::size_t d = kPegDigits.find(ch);
      if (d == std::string_view::npos || d >= head.colours)
        throw fail(fmt::format("row {} of \"pegs\": '{}' is not a colour below {}", r, ch, head.colours));
      pegs.push_back(Colour(d));
    }
  }
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
  if (t.kind != TileKind::Corner || !t.torus) throw InputError("the peg form is for corner tori only");
  if (t.colours > kPegDigits.size())
    throw InputError(fmt::format("the peg form holds at most {} colours, got {}", kPegDigits.size(), t.colours));
  const std::vector<Colour> pegs = pegs_of_corner_torus(t);
  if (corner_torus_from_pegs(pegs, t.rows, t.cols, t.colours).cells != t.cells)
    throw InputError("neighbouring corners do not match: the tiling is not the window grid of a peg colouring");
  nlohmann::json rows = nlohmann::json::array();
  for (int r = 0; r < t.rows; ++r) {
    std::string row;
    for (int c = 0; c < t.cols; ++c) row += kPegDigits[pegs[std::size_t(r) * std::size_t(t.cols) + std::size_t(c)]];
    rows.push_back(std::move(row));
  }
  return {{"kind", "corner"}, {"colors", t.colours}, {"rows", t.rows}, {"cols", t.cols}, {"torus", true},
          {"pegs", std::move(rows)}};
}

Tiling tiling_from_json(const nlohmann::json& j, const std::string& origin) {
  auto fail = [&](const std::string& what) { return InputError(fmt::format("{}: {}", origin, what)); };
  if (!j.is_object()) throw fail("expected a JSON object");
  auto get_int = [&](const char* key, std::int64_t lo, std::int64_t hi) -> std::int64_t {
    if (!j.contains(key)) throw fail(fmt::format("missing \"{}\"", key));
    if (!j[key].is_number_integer()) throw fail(fmt::format("\"{}\" must be an integer", key));
    auto v = j[key].get<std::int64_t>();
    if (v < lo || v > hi) throw fail(fmt::format("\"{}\" must be between {} and {}, got {}", key, lo, hi, v));
    return v;
  };
  Tiling t;
  if (!j.contains("kind") || !j["kind"].is_string()) throw fail("missing \"kind\" (\"wang\" or \"corner\")");
  if (j["kind"] == "wang") t.kind = TileKind::Wang;
  else if (j["kind"] == "corner") t.kind = TileKind::Corner;
  else throw fail(fmt::format("unknown kind {} (expected \"wang\" or \"corner\")", j["kind"].dump()));
  if (j.contains("horizontal_colors")) {
    t.colours = std::uint32_t(get_int("horizontal_colors", 1, 1 << 16));
    t.vertical_colours = std::uint32_t(get_int("vertical_colors", 1, 1 << 16));
  } else {
    t.colours = std::uint32_t(get_int("colors", 1, 1 << 16));
  }
  t.rows = int(get_int("rows", 1, 1 << 20));
  t.cols = int(get_int("cols", 1, 1 << 20));
  if (std::uint64_t(t.rows) * std::uint64_t(t.cols) > (1ull << 28)) throw fail("grid is too large");
  if (!j.contains("torus") || !j["torus"].is_boolean()) throw fail("missing \"torus\" (true or false)");
  t.torus = j["torus"].get<bool>();
  if (!j.contains("cells") && j.contains("pegs")) return tiling_from_pegs_json(t, j["pegs"], fail);
  if (!j.contains("cells") || !j["cells"].is_array()) throw fail("missing \"cells\" array");
  const auto& cells = j["cells"];
  if (cells.size() != std::size_t(t.rows)) throw fail(fmt::format("\"cells\" has {} rows, expected {}", cells.size(), t.rows));
  t.cells.reserve(std::size_t(t.rows) * std::size_t(t.cols));
  for (int r = 0; r < t.rows; ++r) {
    const auto& row = cells[std::size_t(r)];
    if (!row.is_array() || row.size() != std::size_t(t.cols))
      throw fail(fmt::format("row {} of \"cells\" must be an array of {} tile indices", r, t.cols));
    for (const auto& v : row) {
      if (!v.is_number_integer() || v.get<std::int64_t>() < 0 || v.get<std::int64_t>() > 0xffffffffll)
        throw fail(fmt::format("row {}: {} is not a tile index", r, v.dump()));
      t.cells.push_back(TileIndex(v.get<std::int64_t>()));
    }
  }
  return t;
}

Tiling read_tiling_file(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw InputError(fmt::format("{}: no such file", path));
  std::ifstream in(path, std::ios::binary);
  std::stringstream buf;
  buf << in.rdbuf();
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(buf.str());
  } catch (const nlohmann::json::parse_error& e) {
    throw InputError(fmt::format("{}: invalid JSON: {}", path, e.what()));
  }
  return tiling_from_json(j, path);
}

}  // namespace tilekit
