#include "tilesets/tiling.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

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
