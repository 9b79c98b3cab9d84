#include "tilesets/tile_set_io.hpp"

#include <fmt/format.h>

#include <cerrno>
#include <charconv>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>

#include "tilesets/compact_sets.hpp"
#include "base/error.hpp"
#include "tilesets/reference_data.hpp"

namespace tilekit {

namespace {

constexpr std::int64_t kMaxColour = 1 << 24;

TileSet make_set(TileKind kind, std::vector<std::array<std::int64_t, 4>> rows, std::string name, std::string source,
                 std::int64_t declared, const std::vector<std::string>& where, std::vector<RepeatedTile>* repeated) {
  if (repeated) {  // keep the first of equal tiles, report the others
    std::vector<std::size_t> order(rows.size()), first_of(rows.size());
    for (std::size_t k = 0; k < rows.size(); ++k) order[k] = k;
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return rows[a] < rows[b]; });
    for (std::size_t i = 0; i < order.size(); ++i)
      first_of[order[i]] = i > 0 && rows[order[i]] == rows[order[i - 1]] ? first_of[order[i - 1]] : order[i];
    std::vector<std::array<std::int64_t, 4>> distinct;
    std::vector<std::size_t> position(rows.size());  // of each first occurrence among the distinct tiles
    for (std::size_t k = 0; k < rows.size(); ++k) {
      if (first_of[k] == k) {
        position[k] = distinct.size();
        distinct.push_back(rows[k]);
      } else {
        const auto& r = rows[k];
        repeated->push_back({where[k], position[first_of[k]], {Colour(r[0]), Colour(r[1]), Colour(r[2]), Colour(r[3])}});
      }
    }
    rows = std::move(distinct);
  }
  if (kind == TileKind::Wang) {
    std::vector<WangTile> tiles;
    for (auto& r : rows)  // file order: n s w e
      tiles.push_back({Colour(r[0]), Colour(r[3]), Colour(r[1]), Colour(r[2])});
    return TileSet::wang(std::move(tiles), std::move(name), std::move(source), Colour(declared), Colour(declared));
  }
  std::vector<CornerTile> tiles;
  for (auto& r : rows)  // file order: nw ne sw se
    tiles.push_back({Colour(r[1]), Colour(r[3]), Colour(r[2]), Colour(r[0])});
  return TileSet::corner(std::move(tiles), std::move(name), std::move(source), Colour(declared));
}

std::string stem_of(const std::string& origin) { return std::filesystem::path(origin).stem().string(); }

std::int64_t check_colour(std::int64_t v, std::int64_t declared, const std::string& where) {
  if (v < 0) throw InputError(fmt::format("{}: negative colour {}", where, v));
  if (v >= kMaxColour) throw InputError(fmt::format("{}: colour {} is too large", where, v));
  if (declared > 0 && v >= declared)
    throw InputError(fmt::format("{}: colour {} is out of range for {} colours", where, v, declared));
  return v;
}

TileSet parse_text(std::string_view text, const std::string& origin, std::vector<RepeatedTile>* repeated) {
  TileKind kind = TileKind::Wang;
  std::int64_t declared = 0;
  std::string source;
  std::vector<std::array<std::int64_t, 4>> rows;
  std::vector<std::string> where_of;  // "origin:line" of each tile
  std::istringstream in{std::string(text)};
  std::string line;
  int lineno = 0;
  bool seen_tile = false;
  static const std::regex kind_re(R"(^\s*#\s*kind\s*:\s*(\S+)\s*$)");
  static const std::regex colours_re(R"(^\s*#\s*colou?rs\s*:\s*(\S+)\s*$)");
  static const std::regex source_re(R"(^\s*#\s*source\s*:\s*(.*\S)\s*$)");
  while (std::getline(in, line)) {
    ++lineno;
    const std::string where = fmt::format("{}:{}", origin, lineno);
    std::smatch m;
    const bool comment = line.find_first_not_of(" \t") != std::string::npos && line[line.find_first_not_of(" \t")] == '#';
    if (comment && std::regex_match(line, m, kind_re)) {
      if (seen_tile) throw InputError(fmt::format("{}: '# kind:' must come before the first tile", where));
      if (m[1] == "corner") kind = TileKind::Corner;
      else if (m[1] == "wang") kind = TileKind::Wang;
      else throw InputError(fmt::format("{}: unknown kind '{}' (expected wang or corner)", where, m[1].str()));
      continue;
    }
    if (comment && std::regex_match(line, m, colours_re)) {
      auto s = m[1].str();
      auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), declared);
      if (ec != std::errc() || p != s.data() + s.size() || declared < 1 || declared > 255)
        throw InputError(fmt::format("{}: colours must be between 1 and 255, got '{}'", where, s));
      continue;
    }
    if (comment && std::regex_match(line, m, source_re)) {
      if (source.empty()) source = m[1].str();
      continue;
    }
    if (auto hash = line.find('#'); hash != std::string::npos) line.resize(hash);
    std::istringstream fields(line);
    std::vector<std::string> tok;
    for (std::string t; fields >> t;) tok.push_back(t);
    if (tok.empty()) continue;
    if (tok.size() != 4)
      throw InputError(fmt::format("{}: expected 4 colours ({}), found {} fields", where,
                                   kind == TileKind::Wang ? "n s w e" : "nw ne sw se", tok.size()));
    std::array<std::int64_t, 4> row{};
    for (int k = 0; k < 4; ++k) {
      std::int64_t v = 0;
      auto [p, ec] = std::from_chars(tok[k].data(), tok[k].data() + tok[k].size(), v);
      if (ec == std::errc::result_out_of_range) throw InputError(fmt::format("{}: colour '{}' is too large", where, tok[k]));
      if (ec != std::errc() || p != tok[k].data() + tok[k].size())
        throw InputError(fmt::format("{}: '{}' is not a colour (a non-negative integer)", where, tok[k]));
      row[k] = check_colour(v, declared, where);
    }
    rows.push_back(row);
    where_of.push_back(where);
    seen_tile = true;
  }
  if (rows.empty()) throw InputError(fmt::format("{}: the tile set has no tiles", origin));
  try {
    return make_set(kind, std::move(rows), stem_of(origin), source, declared, where_of, repeated);
  } catch (const InputError& e) {
    throw InputError(fmt::format("{}: {}", origin, e.what()));
  }
}

TileSet parse_json(std::string_view text, const std::string& origin, std::vector<RepeatedTile>* repeated) {
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    throw InputError(fmt::format("{}: invalid JSON: {}", origin, e.what()));
  }
  if (!j.is_object()) throw InputError(fmt::format("{}: expected a JSON object", origin));
  TileKind kind = TileKind::Wang;
  if (j.contains("kind")) {
    if (j["kind"] == "corner") kind = TileKind::Corner;
    else if (j["kind"] != "wang") throw InputError(fmt::format("{}: \"kind\" must be \"wang\" or \"corner\"", origin));
  }
  std::int64_t declared = 0;
  if (j.contains("colors")) {
    if (!j["colors"].is_number_integer() || j["colors"].get<std::int64_t>() < 1 || j["colors"].get<std::int64_t>() > 255)
      throw InputError(fmt::format("{}: \"colors\" must be an integer between 1 and 255", origin));
    declared = j["colors"].get<std::int64_t>();
  }
  if (!j.contains("tiles") || !j["tiles"].is_array()) throw InputError(fmt::format("{}: missing \"tiles\" array", origin));
  std::vector<std::array<std::int64_t, 4>> rows;
  std::vector<std::string> where_of;
  for (std::size_t k = 0; k < j["tiles"].size(); ++k) {
    const auto& t = j["tiles"][k];
    const std::string where = fmt::format("{}: tile {}", origin, k + 1);
    if (!t.is_array() || t.size() != 4) throw InputError(fmt::format("{}: expected an array of 4 colours", where));
    std::array<std::int64_t, 4> row{};
    for (int c = 0; c < 4; ++c) {
      if (!t[c].is_number_integer()) throw InputError(fmt::format("{}: colour {} is not an integer", where, t[c].dump()));
      row[c] = check_colour(t[c].get<std::int64_t>(), declared, where);
    }
    rows.push_back(row);
    where_of.push_back(where);
  }
  if (rows.empty()) throw InputError(fmt::format("{}: the tile set has no tiles", origin));
  std::string name = j.value("name", stem_of(origin));
  std::string source = j.value("source", std::string());
  try {
    return make_set(kind, std::move(rows), name, source, declared, where_of, repeated);
  } catch (const InputError& e) {
    throw InputError(fmt::format("{}: {}", origin, e.what()));
  }
}

std::uint32_t parse_count(const std::string& s, const std::string& name) {
  std::int64_t v = 0;
  auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || p != s.data() + s.size())
    throw InputError(fmt::format("tile set '{}': '{}' is not a colour count", name, s));
  check_colour_count(v);
  return std::uint32_t(v);
}

}  // namespace

TileSet parse_tile_set(std::string_view text, const std::string& origin, std::vector<RepeatedTile>* repeated) {
  auto first = text.find_first_not_of(" \t\r\n");
  if (first != std::string_view::npos && text[first] == '{') return parse_json(text, origin, repeated);
  return parse_text(text, origin, repeated);
}

TileSet read_tile_set_file(const std::string& path, std::vector<RepeatedTile>* repeated) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw InputError(fmt::format("{}: no such tile-set file", path));
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(fmt::format("{}: cannot open: {}", path, std::strerror(errno)));
  std::stringstream buf;
  buf << in.rdbuf();
  return parse_tile_set(buf.str(), path, repeated);
}

std::string format_tile_set_text(const TileSet& set) {
  std::string out;
  if (set.kind() == TileKind::Corner) out += "# kind: corner\n";
  if (!set.source().empty()) out += fmt::format("# source: {}\n", set.source());
  out += set.kind() == TileKind::Wang ? "# format: n s w e (one tile per line)\n" : "# format: nw ne sw se (one tile per line)\n";
  for (std::size_t k = 0; k < set.size(); ++k) out += fmt::format("{}\n", fmt::join(set.file_colours(k), " "));
  return out;
}

nlohmann::json tile_set_to_json(const TileSet& set) {
  nlohmann::json tiles = nlohmann::json::array();
  for (std::size_t k = 0; k < set.size(); ++k) tiles.push_back(set.file_colours(k));
  return {{"kind", std::string(kind_name(set.kind()))}, {"name", set.name()}, {"tiles", tiles}};
}

std::vector<BuiltinInfo> builtin_tile_sets() {
  std::vector<BuiltinInfo> out = {
      {"complete-wang-C", "all C^4 Wang tiles over C colours (also complete-wang-HxV: (H*V)^2 tiles)"},
      {"complete-corner-C", "all C^4 corner tiles over C colours"},
      {"compact-wang-C", "2C^2 Wang tiles for scanline stochastic tiling (Cohen et al. 2003)"},
      {"compact-wang3-C", "C^3 Wang tiles for the direct compact algorithm (thesis 3.3.2.2)"},
      {"compact-corner-C", "2C^3 corner tiles for scanline corner tiling (thesis 3.2.2)"},
  };
  for (const EmbeddedFile& f : reference_data()) {
    std::string name(f.name);
    if (!name.ends_with(".tiles")) continue;
    TileSet s = parse_tile_set(f.text, name);
    out.push_back({stem_of(name), fmt::format("{} ({} tiles)", s.source(), s.size())});
  }
  return out;
}

TileSet resolve_tile_set(const std::string& name, std::vector<RepeatedTile>* repeated) {
  static const std::regex family_re(R"(^(complete-wang|complete-corner|compact-wang|compact-wang3|compact-corner)-(\d+)$)");
  static const std::regex mixed_re(R"(^complete-wang-(\d+)x(\d+)$)");
  std::smatch m;
  if (std::regex_match(name, m, mixed_re))
    return complete_wang_set(parse_count(m[1], name), parse_count(m[2], name));
  if (std::regex_match(name, m, family_re)) {
    const std::uint32_t c = parse_count(m[2], name);
    const std::string fam = m[1];
    if (fam == "complete-wang") return complete_wang_set(c, c);
    if (fam == "complete-corner") return complete_corner_set(c);
    if (fam == "compact-wang") return compact_wang_set(c);
    if (fam == "compact-wang3") return compact_wang3_set(c);
    return compact_corner_set(c);
  }
  for (const EmbeddedFile& f : reference_data())
    if (f.name == name + ".tiles") return parse_tile_set(f.text, std::string(f.name));
  std::error_code ec;
  if (std::filesystem::exists(name, ec)) return read_tile_set_file(name, repeated);
  throw InputError(fmt::format("unknown tile set '{}': not a built-in name (see `tilekit tileset list`) or a file", name));
}

}  // namespace tilekit
