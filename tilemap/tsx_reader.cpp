#include "tilemap/tsx_reader.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <map>
#include <pugixml.hpp>

#include "base/error.hpp"
#include "base/input.hpp"
#include "tilemap/wang_id.hpp"

namespace tilekit::tilemap {

namespace {

// pugixml parses without recursion and expands no user-defined entities, so the file's size
// bound (kMaxTsxBytes) bounds the work and the memory.
pugi::xml_node wang_set_node(const pugi::xml_document& doc, const std::string& origin, const std::string& wanted) {
  const pugi::xml_node tileset = doc.child("tileset");
  if (!tileset) {
    if (doc.child("map"))
      throw InputError(fmt::format("{}: a Tiled map; Tilekit reads Wang sets from a tileset file (.tsx)", origin));
    throw InputError(fmt::format("{}: no <tileset> element (not a Tiled tileset file)", origin));
  }
  std::vector<std::string> names;
  for (const pugi::xml_node ws : tileset.child("wangsets").children("wangset")) {
    if (wanted.empty() || wanted == ws.attribute("name").value()) return ws;
    names.emplace_back(ws.attribute("name").value());
  }
  if (names.empty()) throw InputError(fmt::format("{}: the tileset has no Wang set", origin));
  throw InputError(
      fmt::format("{}: no Wang set named \"{}\" (the file has: {})", origin, wanted, fmt::join(names, ", ")));
}

TileKind wang_set_kind(const pugi::xml_node ws, const std::string& where) {
  if (ws.child("wangcornercolor") || ws.child("wangedgecolor"))
    throw InputError(
        fmt::format("{}: a Wang set in the format of Tiled before 1.5; open and save the file in "
                    "Tiled 1.5 or later",
                    where));
  const std::string type = ws.attribute("type").value();
  if (type == "corner") return TileKind::Corner;
  if (type == "edge") return TileKind::Wang;
  if (type == "mixed")
    throw InputError(
        fmt::format("{}: a Wang set of type \"mixed\" (corners and edges); Tilekit represents corner "
                    "sets and edge (Wang) sets only",
                    where));
  throw InputError(fmt::format("{}: Wang set type \"{}\" is not corner, edge or mixed", where, type.substr(0, 32)));
}

int tile_id_of(const pugi::xml_node wt, const std::string& where) {
  const std::string text = wt.attribute("tileid").value();
  std::size_t used = 0;
  long long id = -1;
  try {
    id = std::stoll(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (text.empty() || used != text.size() || id < 0 || id > (1ll << 30))
    throw InputError(fmt::format("{}: tileid \"{}\" is not a tile id", where, text.substr(0, 32)));
  return int(id);
}

}  // namespace

ImportedWangSet parse_tiled_wang_set(const std::string& text, const std::string& origin, const std::string& wangset) {
  require_utf8(text, origin);
  pugi::xml_document doc;
  const pugi::xml_parse_result parsed =
      doc.load_buffer(text.data(), text.size(), pugi::parse_default, pugi::encoding_utf8);
  if (!parsed)
    throw InputError(fmt::format("{}: not XML ({} at byte {})", origin, parsed.description(), parsed.offset));
  const pugi::xml_node ws = wang_set_node(doc, origin, wangset);
  const std::string where =
      fmt::format("{}: Wang set \"{}\"", origin, std::string(ws.attribute("name").value()).substr(0, 64));
  const TileKind kind = wang_set_kind(ws, where);
  ImportedWangSet out;
  out.type = kind == TileKind::Corner ? "corner" : "edge";
  for (const pugi::xml_node wc : ws.children("wangcolor")) {
    if (out.colour_names.size() == kMaxTiledColours)
      throw InputError(fmt::format("{}: more than {} colours", where, kMaxTiledColours));
    out.colour_names.emplace_back(wc.attribute("name").value());
  }
  const auto colours = std::uint32_t(out.colour_names.size());
  if (colours == 0) throw InputError(fmt::format("{}: the Wang set has no colours", where));
  std::map<TileIndex, int> first_id;  // tile index -> first Tiled tile id, in index order
  std::map<int, TileIndex> index_of_id;  // every tile id -> its tile index
  std::vector<CornerTile> corner;
  std::vector<WangTile> wang;
  for (const pugi::xml_node wt : ws.children("wangtile")) {
    const int id = tile_id_of(wt, where);
    const std::string at = fmt::format("{}, tile {}", where, id);
    const WangId wid = parse_wang_id(wt.attribute("wangid").value(), at);
    ++out.wang_tiles;
    if (index_of_id.count(id))
      throw InputError(fmt::format("{}: tile {} has two <wangtile> entries", where, id));
    TileIndex index = 0;
    if (kind == TileKind::Corner) {
      const CornerTile t = corner_tile_of(wid, colours, at);
      index = corner_index(t, colours);
      if (first_id.emplace(index, id).second) corner.push_back(t);
    } else {
      const WangTile t = wang_tile_of(wid, colours, at);
      index = wang_index(t, colours);
      if (first_id.emplace(index, id).second) wang.push_back(t);
    }
    index_of_id[id] = index;
  }
  if (first_id.empty()) throw InputError(fmt::format("{}: the Wang set has no tiles (no <wangtile>)", where));
  const std::string name = ws.attribute("name").value();
  out.set = kind == TileKind::Corner ? TileSet::corner(std::move(corner), name, origin, colours)
                                     : TileSet::wang(std::move(wang), name, origin, colours, colours);
  out.tile_ids.reserve(out.set.size());
  for (std::size_t k = 0; k < out.set.size(); ++k) out.tile_ids.push_back(first_id.at(out.set.index_of(k)));
  for (const auto& [id, index] : index_of_id) out.tile_of_id[id] = *out.set.find_index(index);
  return out;
}

ImportedWangSet read_tiled_wang_set(const std::string& path, const std::string& wangset) {
  return parse_tiled_wang_set(read_input_file(path, "Tiled tileset", kMaxTsxBytes), path, wangset);
}

}  // namespace tilekit::tilemap
