#include "tilemap/tmx_reader.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <pugixml.hpp>

#include "base/error.hpp"
#include "base/input.hpp"
#include "tilemap/tsx_reader.hpp"

namespace tilekit::tilemap {

namespace {

// Tiled's flags in the top bits of a gid (horizontal, vertical, diagonal flip; hexagonal 120°).
constexpr std::uint32_t kFlipBits = 0xF0000000u;
constexpr int kMaxSide = 1 << 15;

int positive_attribute(const pugi::xml_node n, const char* name, const std::string& where) {
  const std::string text = n.attribute(name).value();
  std::size_t used = 0;
  long long v = -1;
  try {
    v = std::stoll(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (text.empty() || used != text.size() || v < 1 || v > kMaxSide)
    throw InputError(
        fmt::format("{}: {}=\"{}\" is not a whole number from 1 to {}", where, name, text.substr(0, 32), kMaxSide));
  return int(v);
}

// One gid of the layer's text: a decimal number below 2^32.
std::uint32_t parse_gid(const std::string& token, const std::string& where, std::size_t k) {
  std::uint64_t v = 0;
  if (token.empty() || token.size() > 10)
    throw InputError(fmt::format("{}: cell {} is \"{}\", not a gid", where, k, token.substr(0, 16)));
  for (char c : token) {
    if (c < '0' || c > '9')
      throw InputError(fmt::format("{}: cell {} is \"{}\", not a gid", where, k, token.substr(0, 16)));
    v = v * 10 + std::uint64_t(c - '0');
  }
  if (v > 0xFFFFFFFFull) throw InputError(fmt::format("{}: cell {}: gid {} is above 2^32", where, k, token));
  return std::uint32_t(v);
}

std::vector<std::uint32_t> csv_gids(const std::string& text, const std::string& where, std::size_t cells) {
  std::vector<std::uint32_t> out;
  std::string token;
  auto flush = [&] {
    if (out.size() == cells) throw InputError(fmt::format("{}: more than the layer's {} cells", where, cells));
    out.push_back(parse_gid(token, where, out.size()));
    token.clear();
  };
  bool any = false;
  for (char c : text) {
    if (c == ',') {
      flush();
      any = false;
    } else if (c != ' ' && c != '\n' && c != '\r' && c != '\t') {
      token += c;
      any = true;
      if (token.size() > 16) throw InputError(fmt::format("{}: cell {} is not a gid", where, out.size()));
    }
  }
  if (any) flush();
  return out;
}

TmxTilesetRef tileset_ref(const pugi::xml_node ts, const std::string& map_path) {
  TmxTilesetRef ref;
  const std::string where = fmt::format("{}: <tileset>", map_path);
  const std::string first = ts.attribute("firstgid").value();
  std::size_t used = 0;
  long long fg = -1;
  try {
    fg = std::stoll(first, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (first.empty() || used != first.size() || fg < 1 || fg >= (1ll << 28))
    throw InputError(fmt::format("{}: firstgid \"{}\" is not a gid", where, first.substr(0, 32)));
  ref.firstgid = std::uint32_t(fg);
  ref.source = ts.attribute("source").value();
  if (ref.source.empty())
    throw InputError(
        fmt::format("{} at firstgid {} is embedded in the map; Tilekit reads tilesets from their own "
                    ".tsx files (in Tiled: Export Tileset, then use the file)",
                    where, fg));
  ref.path = (std::filesystem::path(map_path).parent_path() / ref.source).string();
  ref.text = read_input_file(ref.path, "Tiled tileset", kMaxTsxBytes);
  pugi::xml_document doc;
  if (!doc.load_buffer(ref.text.data(), ref.text.size(), pugi::parse_default, pugi::encoding_utf8) ||
      !doc.child("tileset"))
    throw InputError(fmt::format("{}: not a Tiled tileset (the map {} uses it)", ref.path, map_path));
  const pugi::xml_node root = doc.child("tileset");
  ref.tilecount = positive_attribute(root, "tilecount", ref.path);
  ref.name = root.attribute("name").value();
  return ref;
}

}  // namespace

PaintedMap parse_painted_map(const std::string& text, const std::string& path) {
  require_utf8(text, path);
  pugi::xml_document doc;
  const pugi::xml_parse_result parsed =
      doc.load_buffer(text.data(), text.size(), pugi::parse_default, pugi::encoding_utf8);
  if (!parsed) throw InputError(fmt::format("{}: not XML ({} at byte {})", path, parsed.description(), parsed.offset));
  const pugi::xml_node map = doc.child("map");
  if (!map) throw InputError(fmt::format("{}: no <map> element (not a Tiled map)", path));
  PaintedMap m;
  m.path = path;
  if (std::string(map.attribute("infinite").value()) == "1")
    throw InputError(
        fmt::format("{}: an infinite map; Tilekit fills maps of a fixed size (Map > Map Properties > "
                    "Infinite off)",
                    path));
  const std::string orientation = map.attribute("orientation").value();
  if (orientation != "orthogonal")
    throw InputError(
        fmt::format("{}: orientation \"{}\"; Tilekit fills orthogonal maps", path, orientation.substr(0, 32)));
  m.width = positive_attribute(map, "width", path);
  m.height = positive_attribute(map, "height", path);
  m.tile_width = positive_attribute(map, "tilewidth", path);
  m.tile_height = positive_attribute(map, "tileheight", path);
  if (std::int64_t(m.width) * m.height > (std::int64_t(1) << 28))
    throw InputError(fmt::format("{}: {}x{} cells is too large a map", path, m.width, m.height));
  const pugi::xml_node layer = map.child("layer");
  if (!layer) throw InputError(fmt::format("{}: the map has no tile layer", path));
  m.layer = layer.attribute("name").value();
  const std::string where = fmt::format("{}: layer \"{}\"", path, m.layer.substr(0, 64));
  if (positive_attribute(layer, "width", where) != m.width || positive_attribute(layer, "height", where) != m.height)
    throw InputError(fmt::format("{}: the layer's size is not the map's {}x{}", where, m.width, m.height));
  const pugi::xml_node data = layer.child("data");
  if (!data) throw InputError(fmt::format("{}: no <data>", where));
  const std::string encoding = data.attribute("encoding").value();
  const std::size_t cells = std::size_t(m.width) * std::size_t(m.height);
  if (!std::string(data.attribute("compression").value()).empty() || encoding == "base64")
    throw InputError(fmt::format("{}: data in {}; save the map with Tile Layer Format CSV (Map > Map Properties)",
                                 where, encoding.substr(0, 16)));
  if (encoding == "csv") {
    m.gids = csv_gids(data.text().get(), where, cells);
  } else if (encoding.empty()) {  // Tiled's XML format: one <tile gid="..."/> per cell
    for (const pugi::xml_node t : data.children("tile")) {
      if (m.gids.size() == cells) throw InputError(fmt::format("{}: more than the layer's {} cells", where, cells));
      const std::string g = t.attribute("gid").value();
      m.gids.push_back(g.empty() ? 0 : parse_gid(g, where, m.gids.size()));
    }
  } else {
    throw InputError(fmt::format("{}: unknown encoding \"{}\"", where, encoding.substr(0, 16)));
  }
  if (m.gids.size() != cells)
    throw InputError(fmt::format("{}: {} cells, the map is {}x{}", where, m.gids.size(), m.width, m.height));
  for (std::size_t k = 0; k < cells; ++k)
    if (m.gids[k] & kFlipBits)
      throw InputError(
          fmt::format("{}: the cell at column {}, row {} is flipped or rotated; Tilekit fills with the "
                      "tiles as drawn",
                      where, k % std::size_t(m.width), k / std::size_t(m.width)));
  // the tilesets last, so that a map's own problems are named first (and fuzzed without files)
  for (const pugi::xml_node ts : map.children("tileset")) m.tilesets.push_back(tileset_ref(ts, path));
  if (m.tilesets.empty()) throw InputError(fmt::format("{}: the map uses no tileset", path));
  std::sort(m.tilesets.begin(), m.tilesets.end(),
            [](const TmxTilesetRef& a, const TmxTilesetRef& b) { return a.firstgid < b.firstgid; });
  return m;
}

PaintedMap read_painted_map(const std::string& path) {
  return parse_painted_map(read_input_file(path, "Tiled map", kMaxTsxBytes), path);
}

int tileset_of_gid(const PaintedMap& m, std::uint32_t gid) {
  int found = -1;
  for (std::size_t k = 0; k < m.tilesets.size(); ++k)
    if (gid != 0 && m.tilesets[k].firstgid <= gid) found = int(k);
  return found;
}

}  // namespace tilekit::tilemap
