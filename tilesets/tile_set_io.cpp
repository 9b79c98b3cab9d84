#include "tilesets/tile_set_io.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <charconv>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>

#include "base/error.hpp"
#include "base/input.hpp"
#include "base/json_input.hpp"
#include "tilesets/compact_sets.hpp"
#include "tilesets/reference_data.hpp"

namespace tilekit {

namespace {

// One tile as read, in file order (n s w e or nw ne sw se), and where it was read.
struct RawTile {
  std::array<std::int64_t, 4> colours{};
  std::string where;  // "file:line" or "file: tiles[k]"
};

TileSet make_set(TileKind kind, std::vector<RawTile> rows, std::string name, std::string source,
                 std::int64_t declared, const std::string& origin, std::vector<RepeatedTile>* repeated) {
  // Equal tiles, found by sorting (stable: the first in file order leads each run). Without
  // `repeated` a repeat is an error naming both places; with it, the set keeps the first of
  // equal tiles (in file order) and the others are listed there.
  std::vector<std::size_t> order(rows.size()), first_of(rows.size());
  for (std::size_t k = 0; k < rows.size(); ++k) order[k] = k;
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return rows[a].colours < rows[b].colours; });
  bool any = false;
  for (std::size_t i = 0; i < order.size(); ++i) {
    const bool repeat = i > 0 && rows[order[i]].colours == rows[order[i - 1]].colours;
    first_of[order[i]] = repeat ? first_of[order[i - 1]] : order[i];
    any = any || repeat;
  }
  if (any && !repeated) {
    std::size_t k = 0;  // the earliest repeat in file order
    while (first_of[k] == k) ++k;
    throw InputError(fmt::format("{}: duplicate tile: repeats the tile of {} ({})", rows[k].where,
                                 rows[first_of[k]].where, fmt::join(rows[k].colours, " ")));
  }
  if (any) {
    std::vector<RawTile> distinct;
    std::vector<std::size_t> position(rows.size());  // of each first occurrence among the distinct tiles
    for (std::size_t k = 0; k < rows.size(); ++k) {
      const auto& r = rows[k].colours;
      if (first_of[k] == k) {
        position[k] = distinct.size();
        distinct.push_back(rows[k]);
      } else {
        repeated->push_back(
            {rows[k].where, position[first_of[k]], {Colour(r[0]), Colour(r[1]), Colour(r[2]), Colour(r[3])}});
      }
    }
    rows = std::move(distinct);
  }
  try {
    if (kind == TileKind::Wang) {
      std::vector<WangTile> tiles;
      tiles.reserve(rows.size());
      for (const RawTile& t : rows) {  // file order: n s w e
        const auto& r = t.colours;
        tiles.push_back({Colour(r[0]), Colour(r[3]), Colour(r[1]), Colour(r[2])});
      }
      TileSet set =
          TileSet::wang(std::move(tiles), std::move(name), std::move(source), Colour(declared), Colour(declared));
      if (std::uint64_t(set.horizontal_radix()) * set.vertical_radix() > kMaxWangColourProduct)
        throw InputError(
            fmt::format("a Wang set over {}x{} colours is too large: tile indices (thesis eq. 2.2) are "
                        "32-bit, so C_h * C_v must be at most {}",
                        set.horizontal_radix(), set.vertical_radix(), kMaxWangColourProduct));
      return set;
    }
    std::vector<CornerTile> tiles;
    tiles.reserve(rows.size());
    for (const RawTile& t : rows) {  // file order: nw ne sw se
      const auto& r = t.colours;
      tiles.push_back({Colour(r[1]), Colour(r[3]), Colour(r[2]), Colour(r[0])});
    }
    return TileSet::corner(std::move(tiles), std::move(name), std::move(source), Colour(declared));
  } catch (const InputError& e) {
    throw InputError(fmt::format("{}: {}", origin, e.what()));
  }
}

std::string stem_of(const std::string& origin) {
  return utf8_or_question_marks(std::filesystem::path(origin).stem().string());
}

std::int64_t check_colour(std::int64_t v, std::int64_t declared, const std::string& where) {
  if (v < 0) throw InputError(fmt::format("{}: negative colour {}", where, v));
  if (v > kMaxTileSetColour)
    throw InputError(fmt::format("{}: colour {} is too large (at most {})", where, v, kMaxTileSetColour));
  if (declared > 0 && v >= declared)
    throw InputError(fmt::format("{}: colour {} is out of range for {} colours", where, v, declared));
  return v;
}

constexpr std::string_view kSpace = " \t\r\v\f";

std::string_view trim(std::string_view s) {
  const auto a = s.find_first_not_of(kSpace);
  if (a == std::string_view::npos) return {};
  return s.substr(a, s.find_last_not_of(kSpace) - a + 1);
}

// Names and sources end up in one-line comments of the text format and in JSON: one line of
// printable text.
std::string check_label(std::string_view label, const char* what, const std::string& where) {
  const std::string text(trim(label));  // as a text file's "# source:" line reads back
  if (text.size() > 4096) throw InputError(fmt::format("{}: the {} is longer than 4096 bytes", where, what));
  for (char c : text)
    if (static_cast<unsigned char>(c) < 0x20 && c != '\t')
      throw InputError(fmt::format("{}: the {} holds a control character (it must be one line of text)", where, what));
  return text;
}

// "# KEY: VALUE" (spaces allowed around each part) -> VALUE trimmed; nullopt for any other
// line. A hand-written scanner: std::regex recurses per character and overflows the stack
// on a long comment line.
std::optional<std::string_view> directive(std::string_view line, std::initializer_list<std::string_view> keys) {
  line = trim(line);
  if (line.empty() || line.front() != '#') return std::nullopt;
  line = trim(line.substr(1));
  for (std::string_view key : keys) {
    if (!line.starts_with(key)) continue;
    std::string_view rest = trim(line.substr(key.size()));
    if (rest.empty() || rest.front() != ':') continue;
    return trim(rest.substr(1));
  }
  return std::nullopt;
}

TileSet parse_text(std::string_view text, const std::string& origin, std::vector<RepeatedTile>* repeated) {
  require_utf8(text, origin);
  TileKind kind = TileKind::Wang;
  std::int64_t declared = 0;
  std::string source;
  std::vector<RawTile> rows;
  int lineno = 0;
  for (std::size_t pos = 0; pos < text.size();) {
    const std::size_t eol = std::min(text.find('\n', pos), text.size());
    std::string_view line = text.substr(pos, eol - pos);
    pos = eol + 1;
    ++lineno;
    const std::string where = fmt::format("{}:{}", origin, lineno);
    if (auto v = directive(line, {"kind"})) {
      if (!rows.empty()) throw InputError(fmt::format("{}: '# kind:' must come before the first tile", where));
      if (*v == "corner")
        kind = TileKind::Corner;
      else if (*v == "wang")
        kind = TileKind::Wang;
      else
        throw InputError(fmt::format("{}: unknown kind '{}' (expected wang or corner)", where, v->substr(0, 40)));
      continue;
    }
    if (auto v = directive(line, {"colours", "colors"})) {
      auto [p, ec] = std::from_chars(v->data(), v->data() + v->size(), declared);
      if (ec != std::errc() || p != v->data() + v->size() || declared < 1 || declared > kMaxTileSetColour + 1)
        throw InputError(fmt::format("{}: colours must be between 1 and {}, got '{}'", where, kMaxTileSetColour + 1,
                                     v->substr(0, 40)));
      continue;
    }
    if (auto v = directive(line, {"source"})) {
      if (source.empty()) source = check_label(*v, "source", where);
      continue;
    }
    if (auto hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
    std::string_view fields[5];
    int n = 0;
    for (std::size_t i = 0; n < 5;) {
      i = line.find_first_not_of(kSpace, i);
      if (i == std::string_view::npos) break;
      const std::size_t j = std::min(line.find_first_of(kSpace, i), line.size());
      fields[n++] = line.substr(i, j - i);
      i = j;
    }
    if (n == 0) continue;
    if (n != 4)
      throw InputError(fmt::format("{}: expected 4 colours ({}), found {} fields", where,
                                   kind == TileKind::Wang ? "n s w e" : "nw ne sw se",
                                   n == 5 ? "more than 4" : std::to_string(n)));
    if (rows.size() >= kMaxTiles) throw InputError(fmt::format("{}: more than {} tiles", where, kMaxTiles));
    RawTile tile{{}, where};
    for (int k = 0; k < 4; ++k) {
      const std::string_view f = fields[k];
      std::int64_t v = 0;
      auto [p, ec] = std::from_chars(f.data(), f.data() + f.size(), v);
      if (ec == std::errc::result_out_of_range)
        throw InputError(fmt::format("{}: colour '{}' is too large", where, f.substr(0, 40)));
      if (ec != std::errc() || p != f.data() + f.size())
        throw InputError(fmt::format("{}: '{}' is not a colour (a non-negative integer)", where, f.substr(0, 40)));
      tile.colours[std::size_t(k)] = check_colour(v, declared, where);
    }
    rows.push_back(std::move(tile));
  }
  if (rows.empty()) throw InputError(fmt::format("{}: the tile set has no tiles", origin));
  return make_set(kind, std::move(rows), stem_of(origin), source, declared, origin, repeated);
}

// The tile-set JSON format {"kind", "name", "source", "colors", "tiles": [[...], ...]}, and
// also what `tilekit tileset show --json` prints (there "tiles" is the count and "list" the
// tiles; "colors" is then the number of colours used, not a declared radix).
TileSet parse_json(std::string_view text, const std::string& origin, std::vector<RepeatedTile>* repeated) {
  const nlohmann::json doc = parse_json_input(text, origin);
  const JsonIn j(doc, origin);
  j.object();
  TileKind kind = TileKind::Wang;
  if (auto k = j.find("kind")) {
    const std::string v = k->string();
    if (v == "corner")
      kind = TileKind::Corner;
    else if (v != "wang")
      throw k->error("must be \"wang\" or \"corner\"");
  }
  const bool show_format = j.has("list");
  const JsonIn list = j.at(show_format ? "list" : "tiles");
  const std::size_t n = list.array(1, kMaxTiles);
  std::int64_t declared = 0;
  if (show_format) {
    if (auto count = j.find("tiles"); count && count->unsigned_integer() != n)
      throw count->error(fmt::format("says {} tiles but \"list\" holds {}", count->raw().dump(), n));
  } else if (auto c = j.find("colors")) {
    declared = c->integer(1, kMaxTileSetColour + 1);
  }
  std::vector<RawTile> rows;
  rows.reserve(n);
  for (std::size_t k = 0; k < n; ++k) {
    const JsonIn t = list[k];
    t.array(4, 4);
    RawTile tile{{}, fmt::format("{}: {}", origin, t.path())};
    for (std::size_t c = 0; c < 4; ++c)
      tile.colours[c] = check_colour(t[c].integer(0, kMaxTileSetColour), declared, tile.where);
    rows.push_back(std::move(tile));
  }
  std::string name = check_label(j.string_or("name", stem_of(origin)), "name", origin);
  std::string source = check_label(j.string_or("source", ""), "source", origin);
  TileSet set = make_set(kind, std::move(rows), std::move(name), std::move(source), declared, origin, repeated);
  if (auto c = j.find("colors"); show_format && c && c->unsigned_integer() != set.colours())
    throw c->error(fmt::format("says {} colours but the tiles use {}", c->raw().dump(), set.colours()));
  return set;
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
  return parse_tile_set(read_input_file(path, "tile-set file"), path, repeated);
}

std::string format_tile_set_text(const TileSet& set) {
  std::string out;
  if (set.kind() == TileKind::Corner) out += "# kind: corner\n";
  if (!set.source().empty()) out += fmt::format("# source: {}\n", set.source());
  out += set.kind() == TileKind::Wang ? "# format: n s w e (one tile per line)\n"
                                      : "# format: nw ne sw se (one tile per line)\n";
  for (std::size_t k = 0; k < set.size(); ++k) out += fmt::format("{}\n", fmt::join(set.file_colours(k), " "));
  return out;
}

nlohmann::json tile_set_to_json(const TileSet& set) {
  nlohmann::json tiles = nlohmann::json::array();
  for (std::size_t k = 0; k < set.size(); ++k) tiles.push_back(set.file_colours(k));
  nlohmann::json j = {{"kind", std::string(kind_name(set.kind()))}, {"name", set.name()}, {"tiles", tiles}};
  if (!set.source().empty()) j["source"] = set.source();  // so that the JSON form reads back whole
  return j;
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
  // FAMILY-C and complete-wang-HxV; the longest family names first (compact-wang3 before
  // compact-wang).
  static constexpr std::string_view kFamilies[] = {"complete-corner", "complete-wang", "compact-corner",
                                                   "compact-wang3", "compact-wang"};
  auto digits = [](std::string_view s) {
    return !s.empty() && s.find_first_not_of("0123456789") == std::string_view::npos;
  };
  for (std::string_view fam : kFamilies) {
    const std::string_view n(name);
    if (n.size() <= fam.size() + 1 || !n.starts_with(fam) || n[fam.size()] != '-') continue;
    const std::string_view arg = n.substr(fam.size() + 1);
    if (fam == "complete-wang") {
      const auto x = arg.find('x');
      if (x != std::string_view::npos && digits(arg.substr(0, x)) && digits(arg.substr(x + 1)))
        return complete_wang_set(parse_count(std::string(arg.substr(0, x)), name),
                                 parse_count(std::string(arg.substr(x + 1)), name));
    }
    if (!digits(arg)) break;
    const std::uint32_t c = parse_count(std::string(arg), name);
    if (fam == "complete-wang") return complete_wang_set(c, c);
    if (fam == "complete-corner") return complete_corner_set(c);
    if (fam == "compact-wang") return compact_wang_set(c);
    if (fam == "compact-wang3") return compact_wang3_set(c);
    return compact_corner_set(c);
  }
  for (const EmbeddedFile& f : reference_data())
    if (f.name == name + ".tiles") return parse_tile_set(f.text, std::string(f.name), repeated);
  std::error_code ec;
  if (std::filesystem::exists(name, ec)) return read_tile_set_file(name, repeated);
  throw InputError(
      fmt::format("unknown tile set '{}': not a built-in name (see `tilekit tileset list`) or a file", name));
}

}  // namespace tilekit
