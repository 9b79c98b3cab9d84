#include "tilemap/fill_job.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <pugixml.hpp>
#include <set>
#include <sstream>

#include "atlas/render.hpp"
#include "base/atomic_file.hpp"
#include "base/error.hpp"
#include "base/input.hpp"
#include "image/image.hpp"
#include "solver/fill_sat.hpp"
#include "tilemap/blob_set.hpp"
#include "tilemap/tiled_files.hpp"
#include "tilemap/tiled_tileset.hpp"
#include "tilemap/tmx_reader.hpp"
#include "tilemap/tsx_reader.hpp"
#include "tilemap/wfc_tileset.hpp"
#include "tilemap/xml_text.hpp"
#include "tilesets/tile_set_io.hpp"
#include "tilesets/validator.hpp"

namespace tilekit::tilemap {

namespace {

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

struct LoadedSet {
  std::string source;
  std::optional<TileSet> set;           // tileset and tiled
  std::optional<ImportedWangSet> tiled;  // tiled
  std::string tsx_path;
  std::optional<WfcTileset> wfc;  // wfc
  std::vector<std::string> names;
  std::vector<double> weights;
};

// The tile of a Tilekit set as its four edge labels N E S W (a corner tile's edge is its two corners).
std::array<std::uint64_t, 4> edge_labels(const TileSet& s, std::size_t k) {
  if (s.kind() == TileKind::Wang) {
    const WangTile& t = s.wang_tiles()[k];
    return {t.n, t.e, t.s, t.w};
  }
  const CornerTile& t = s.corner_tiles()[k];
  auto pair = [](Colour a, Colour b) { return (std::uint64_t(a) << 32) | b; };
  // north edge: nw, ne; east: ne, se; south: sw, se; west: nw, sw (read west to east, north to south)
  return {pair(t.nw, t.ne), pair(t.ne, t.se), pair(t.sw, t.se), pair(t.nw, t.sw)};
}

LoadedSet load_set(const FillJobRequest& req) {
  LoadedSet ls;
  if (ends_with(req.set, ".xml")) {
    ls.source = "wfc";
    ls.wfc = read_wfc_tileset(req.set, req.subset, true);
    ls.names = ls.wfc->names;
    ls.weights = ls.wfc->weights;
    return ls;
  }
  if (!req.subset.empty()) throw RequestError("subset", "`subset` names a subset of a WFC .xml tile set");
  if (ends_with(req.set, ".tsx")) {
    ls.source = "tiled";
    ls.tiled = read_tiled_wang_set(req.set, req.wangset);
    ls.set = ls.tiled->set;
    ls.tsx_path = req.set;
  } else {
    if (!req.wangset.empty()) throw RequestError("wangset", "`wangset` names a Wang set of a Tiled .tsx file");
    ls.source = req.set == "blob-47" ? "blob" : "tileset";
    ls.set = req.set == "blob-47" ? blob_tile_set() : resolve_tile_set(req.set);
  }
  if (ls.set->kind() == TileKind::Window) throw InputError("a window set has no adjacency rules to fill a map with");
  for (std::size_t k = 0; k < ls.set->size(); ++k) ls.names.push_back(std::to_string(k));
  ls.weights.assign(ls.set->size(), 1.0);
  return ls;
}

std::shared_ptr<FillRules> make_rules(const LoadedSet& ls) {
  auto rules = std::make_shared<FillRules>(int(ls.names.size()), ls.weights);
  if (ls.wfc) {
    for (const auto& [d, a, b] : ls.wfc->pairs) rules->allow(a, d, b);
    return rules;
  }
  const std::size_t n = ls.set->size();
  std::vector<std::array<std::uint64_t, 4>> lab(n);
  for (std::size_t k = 0; k < n; ++k) lab[k] = edge_labels(*ls.set, k);
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t b = 0; b < n; ++b) {
      if (lab[a][1] == lab[b][3]) rules->allow(int(a), 1, int(b));  // b east of a
      if (lab[a][2] == lab[b][0]) rules->allow(int(a), 2, int(b));  // b south of a
    }
  return rules;
}

// Tile names a token may use: the number, and for WFC sets "name" (every orientation) or "name k".
std::vector<int> tiles_named(const LoadedSet& ls, const std::string& token) {
  std::vector<int> out;
  if (ls.wfc) {
    std::string t = token;
    for (char& c : t)
      if (c == ':') c = ' ';
    for (std::size_t k = 0; k < ls.names.size(); ++k)
      if (ls.names[k] == t || (t.find(' ') == std::string::npos && ls.names[k].rfind(t + " ", 0) == 0))
        out.push_back(int(k));
    if (!out.empty()) return out;
  }
  std::int64_t v = -1;
  try {
    std::size_t used = 0;
    v = std::stoll(token, &used);
    if (used != token.size()) v = -1;
  } catch (const std::exception&) {
    v = -1;
  }
  if (v >= 0 && v < std::int64_t(ls.names.size())) out.push_back(int(v));
  return out;
}

std::vector<int> read_cells(const LoadedSet& ls, const std::string& path, int rows, int cols, std::size_t& fixed) {
  const std::string text = read_input_file(path, "cells file", std::uint64_t(1) << 30);
  std::vector<int> cells(std::size_t(rows) * std::size_t(cols), -1);
  std::istringstream in(text);
  int r = 0, line_no = 0;
  for (std::string line; std::getline(in, line);) {
    ++line_no;
    std::istringstream ls_in(line);
    std::vector<std::string> tokens;
    for (std::string t; ls_in >> t;) tokens.push_back(t);
    if (tokens.empty() || tokens[0][0] == '#') continue;
    if (r >= rows) throw InputError(fmt::format("{}:{}: more than {} rows", path, line_no, rows));
    if (int(tokens.size()) != cols)
      throw InputError(fmt::format("{}:{}: {} cells, the map is {} wide", path, line_no, tokens.size(), cols));
    for (int c = 0; c < cols; ++c) {
      if (tokens[std::size_t(c)] == ".") continue;
      std::vector<int> t = tiles_named(ls, tokens[std::size_t(c)]);
      if (ls.wfc && wfc_tile_number(*ls.wfc, tokens[std::size_t(c)]) >= 0) t = {wfc_tile_number(*ls.wfc, tokens[std::size_t(c)])};
      if (t.size() != 1)
        throw InputError(fmt::format("{}:{}: \"{}\" is {} tile of the set", path, line_no,
                                     tokens[std::size_t(c)].substr(0, 32), t.empty() ? "no" : "more than one"));
      cells[std::size_t(r) * std::size_t(cols) + std::size_t(c)] = t[0];
      ++fixed;
    }
    ++r;
  }
  if (r != rows) throw InputError(fmt::format("{}: {} rows, the map is {} high", path, r, rows));
  return cells;
}

Tiling as_tiling(const TileSet& set, const std::vector<int>& map, int rows, int cols, bool torus) {
  Tiling t(set.kind(), set.horizontal_radix(), rows, cols, torus);
  t.vertical_colours = set.vertical_radix() == set.horizontal_radix() ? 0 : set.vertical_radix();
  for (std::size_t i = 0; i < map.size(); ++i) {
    const std::size_t k = std::size_t(map[i]);
    t.cells[i] = set.kind() == TileKind::Wang ? wang_index(set.wang_tiles()[k], set.horizontal_radix(), set.vertical_radix())
                                              : corner_index(set.corner_tiles()[k], set.horizontal_radix());
  }
  return t;
}

Image wfc_picture(const WfcTileset& w, const std::vector<int>& map, int rows, int cols) {
  const int px = w.tile_px;
  if (std::int64_t(rows) * cols * px * px > kMaxImagePixels)
    throw InputError(fmt::format("a picture of {}x{} tiles of {} pixels is too large", cols, rows, px));
  Image img(cols * px, rows * px);
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) {
      const Image& tile = w.images[std::size_t(map[std::size_t(r) * std::size_t(cols) + std::size_t(c)])];
      for (int y = 0; y < px; ++y)
        for (int x = 0; x < px; ++x)
          for (int ch = 0; ch < 4; ++ch) img.at(c * px + x, r * px + y)[ch] = tile.at(x, y)[ch];
    }
  return img;
}

struct TmxTilesetLine {
  std::uint32_t firstgid;
  std::string source;
};

std::string gid_tmx(const std::vector<std::uint32_t>& gids, int rows, int cols, int tw, int th,
                    const std::vector<TmxTilesetLine>& tilesets) {
  std::string s = fmt::format(
      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      "<map version=\"1.8\" orientation=\"orthogonal\" renderorder=\"right-down\" width=\"{0}\" height=\"{1}\" "
      "tilewidth=\"{2}\" tileheight=\"{3}\" infinite=\"0\" nextlayerid=\"2\" nextobjectid=\"1\">\n",
      cols, rows, tw, th);
  for (const TmxTilesetLine& t : tilesets)
    s += fmt::format(" <tileset firstgid=\"{}\" source=\"{}\"/>\n", t.firstgid,
                     xml_escape(t.source, "the tileset's file name"));
  s += fmt::format(" <layer id=\"1\" name=\"tiles\" width=\"{}\" height=\"{}\">\n  <data encoding=\"csv\">\n", cols, rows);
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      s += std::to_string(gids[std::size_t(r) * std::size_t(cols) + std::size_t(c)]);
      if (r + 1 < rows || c + 1 < cols) s += ',';
    }
    s += '\n';
  }
  s += "</data>\n </layer>\n</map>\n";
  return s;
}

void make_dir(const std::string& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec || !std::filesystem::is_directory(dir))
    throw InputError(fmt::format("{}: cannot make the output folder ({})", dir, ec ? ec.message() : "not a folder"));
}

// The fixed cells of a map painted in Tiled: each gid's tile of the map's tileset, matched to the
// fill set's tile. WFC sets: the sheet `--tiled` writes (tile id = the tile's number, the tileset
// as many tiles as the set). Tilekit and Tiled sets: the tileset's Wang set, a tile matched by its
// wangid (its edge labels), so a sheet Tilekit wrote, the user's own .tsx and its variants all map.
struct PaintedCells {
  PaintedMap map;
  std::vector<int> cells;                  // fill tile per cell, -1 free
  std::vector<std::uint32_t> gid_of_tile;  // the smallest gid showing each fill tile (0: none)
};

// Tile id -> fill tile of one tileset of the map ("" reason) or why it has none.
struct TilesetTiles {
  std::vector<int> tile;  // by tile id; -1 none
  std::string why;        // the whole tileset is unusable
};

TilesetTiles tileset_tiles(const LoadedSet& ls, const TmxTilesetRef& ref, const std::string& wangset) {
  TilesetTiles out;
  out.tile.assign(std::size_t(ref.tilecount), -1);
  const int n = int(ls.names.size());
  if (ls.wfc) {
    if (ref.tilecount != n)
      out.why = fmt::format("{} has {} tiles, the WFC set {} (paint with the sheet Tilekit writes beside a filled WFC map)", ref.source,
                            ref.tilecount, n);
    else
      for (int t = 0; t < n; ++t) out.tile[std::size_t(t)] = t;
    return out;
  }
  std::optional<ImportedWangSet> imported;
  try {
    std::error_code ec;
    const bool same = !ls.tsx_path.empty() && std::filesystem::equivalent(ls.tsx_path, ref.path, ec);
    imported = parse_tiled_wang_set(ref.text, ref.path, same ? wangset : "");
  } catch (const InputError& e) {
    out.why = e.what();
    return out;
  }
  if (imported->set.kind() != ls.set->kind()) {
    out.why = fmt::format("{}'s Wang set is of type {}, the fill set is a {} set", ref.source, imported->type,
                          ls.set->kind() == TileKind::Corner ? "corner" : "Wang (edge)");
    return out;
  }
  std::map<std::array<std::uint64_t, 4>, int> by_labels;
  for (std::size_t k = 0; k < ls.set->size(); ++k) by_labels.emplace(edge_labels(*ls.set, k), int(k));
  for (const auto& [id, k] : imported->tile_of_id) {
    if (id >= ref.tilecount) continue;
    auto it = by_labels.find(edge_labels(imported->set, k));
    if (it != by_labels.end()) out.tile[std::size_t(id)] = it->second;
  }
  return out;
}

PaintedCells read_painted_cells(const LoadedSet& ls, const FillJobRequest& req, int rows, int cols, std::size_t& fixed) {
  PaintedCells pc{read_painted_map(req.cells), {}, std::vector<std::uint32_t>(ls.names.size(), 0)};
  const PaintedMap& m = pc.map;
  if (ls.source == "blob")
    throw RequestError("cells", "`cells`: the blob set has no Tiled tileset to paint with; use a cells file");
  if (m.width != cols || m.height != rows)
    throw RequestError("size", fmt::format("`size` is {}x{}, the painted map {} is {}x{}", cols, rows, req.cells,
                                           m.width, m.height));
  std::vector<TilesetTiles> tiles;
  for (const TmxTilesetRef& ref : m.tilesets) {
    tiles.push_back(tileset_tiles(ls, ref, req.wangset));
    for (std::size_t id = 0; id < tiles.back().tile.size(); ++id) {
      const int t = tiles.back().tile[id];
      const std::uint32_t gid = ref.firstgid + std::uint32_t(id);
      if (t >= 0 && (pc.gid_of_tile[std::size_t(t)] == 0 || gid < pc.gid_of_tile[std::size_t(t)]))
        pc.gid_of_tile[std::size_t(t)] = gid;
    }
  }
  pc.cells.assign(m.gids.size(), -1);
  for (std::size_t i = 0; i < m.gids.size(); ++i) {
    const std::uint32_t gid = m.gids[i];
    if (gid == 0) continue;
    const std::string at = fmt::format("{}: the cell at column {}, row {} (gid {})", req.cells, i % std::size_t(cols),
                                       i / std::size_t(cols), gid);
    const int ts = tileset_of_gid(m, gid);
    if (ts < 0) throw InputError(at + " is in none of the map's tilesets");
    const TmxTilesetRef& ref = m.tilesets[std::size_t(ts)];
    const std::uint32_t id = gid - ref.firstgid;
    if (id >= std::uint32_t(ref.tilecount))
      throw InputError(fmt::format("{}: tile {} is past the {} tiles of {}", at, id, ref.tilecount, ref.source));
    const TilesetTiles& tt = tiles[std::size_t(ts)];
    if (!tt.why.empty()) throw InputError(fmt::format("{} is no tile of the set: {}", at, tt.why));
    if (tt.tile[id] < 0)
      throw InputError(fmt::format("{}: tile {} of {} is no tile of the set {}", at, id, ref.source, req.set));
    pc.cells[i] = tt.tile[id];
    ++fixed;
  }
  return pc;
}

// The filled map as a .tmx over the painted map's own tilesets: painted cells keep their gid, each
// filled cell gets the smallest gid showing its tile.
void write_painted_tmx(const PaintedCells& pc, const FillJobRequest& req, const std::vector<int>& map,
                       const std::vector<std::string>& names, FillJobOutcome& o) {
  std::vector<std::uint32_t> gids(map.size());
  for (std::size_t i = 0; i < map.size(); ++i) {
    gids[i] = pc.map.gids[i] != 0 ? pc.map.gids[i] : pc.gid_of_tile[std::size_t(map[i])];
    if (gids[i] == 0) throw std::logic_error("no gid for tile " + names[std::size_t(map[i])]);
  }
  make_dir(req.out_tiled);
  std::vector<TmxTilesetLine> lines;
  for (const TmxTilesetRef& ref : pc.map.tilesets)
    lines.push_back({ref.firstgid, std::filesystem::relative(std::filesystem::absolute(ref.path),
                                                             std::filesystem::absolute(req.out_tiled))
                                       .string()});
  o.tmx = (std::filesystem::path(req.out_tiled) / (file_stem(std::filesystem::path(req.cells).stem().string()) + "-fill.tmx"))
              .string();
  o.tsx = pc.map.tilesets.front().path;
  write_file_atomic(o.tmx, gid_tmx(gids, pc.map.height, pc.map.width, pc.map.tile_width, pc.map.tile_height, lines));
}

// The Tiled files of a fill: a tileset and NAME-fill.tmx in `dir`.
void write_tiled(const LoadedSet& ls, const FillJobRequest& req, const std::vector<int>& map, FillJobOutcome& o) {
  const std::string& dir = req.out_tiled;
  const int rows = req.height, cols = req.width;
  std::vector<std::uint32_t> gids(map.size());
  if (ls.wfc) {
    const WfcTileset& w = *ls.wfc;
    const int n = int(w.names.size()), px = w.tile_px;
    Image sheet(n * px, px);
    for (int t = 0; t < n; ++t)
      for (int y = 0; y < px; ++y)
        for (int x = 0; x < px; ++x)
          for (int ch = 0; ch < 4; ++ch) sheet.at(t * px + x, y)[ch] = w.images[std::size_t(t)].at(x, y)[ch];
    const std::string stem = file_stem(w.subset.empty() ? w.name : w.name + "-" + w.subset);
    std::string tsx = fmt::format(
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
        "<tileset version=\"1.8\" name=\"{}\" tilewidth=\"{}\" tileheight=\"{}\" tilecount=\"{}\" columns=\"{}\">\n"
        " <image source=\"{}\" width=\"{}\" height=\"{}\"/>\n</tileset>\n",
        xml_escape(stem, "the tileset name"), px, px, n, n, xml_escape(stem + ".png", "the sheet's file name"), n * px, px);
    for (std::size_t i = 0; i < map.size(); ++i) gids[i] = std::uint32_t(map[i] + 1);
    make_dir(dir);
    o.tsx = (std::filesystem::path(dir) / (stem + ".tsx")).string();
    write_png((std::filesystem::path(dir) / (stem + ".png")).string(), sheet);
    write_file_atomic(o.tsx, tsx);
    o.tmx = (std::filesystem::path(dir) / (stem + "-fill.tmx")).string();
    write_file_atomic(o.tmx, gid_tmx(gids, rows, cols, px, px, {{1, stem + ".tsx"}}));
    return;
  }
  if (ls.tiled) {
    pugi::xml_document doc;
    const std::string text = read_input_file(ls.tsx_path, "Tiled tileset", kMaxTsxBytes);
    doc.load_buffer(text.data(), text.size());
    const int tw = doc.child("tileset").attribute("tilewidth").as_int(16);
    const int th = doc.child("tileset").attribute("tileheight").as_int(16);
    for (std::size_t i = 0; i < map.size(); ++i) gids[i] = std::uint32_t(ls.tiled->tile_ids[std::size_t(map[i])] + 1);
    make_dir(dir);
    const std::string rel = std::filesystem::relative(std::filesystem::absolute(ls.tsx_path),
                                                      std::filesystem::absolute(dir)).string();
    o.tsx = ls.tsx_path;
    o.tmx = (std::filesystem::path(dir) / (file_stem(ls.set->name()) + "-fill.tmx")).string();
    write_file_atomic(o.tmx, gid_tmx(gids, rows, cols, tw, th, {{1, rel}}));
    return;
  }
  const TileSet& s = *ls.set;
  if (ls.source == "blob") throw RequestError("tiled", "`tiled`: no Tiled sheet for the blob set yet (its Wang set is mixed)");
  if (s.horizontal_radix() != s.vertical_radix() || s.horizontal_radix() > kMaxSheetColours)
    throw InputError("a Tiled sheet needs one colour radix of at most 64 colours");
  const TilesetOutcome ts = write_tiled_tileset({s.kind(), s.horizontal_radix(), "", req.tile_px, "", dir, {}, {}});
  const Tiling t = as_tiling(s, map, rows, cols, req.torus);
  o.tsx = ts.tsx_path;
  o.tmx = (std::filesystem::path(dir) / (file_stem(ts.name) + "-fill.tmx")).string();
  write_file_atomic(o.tmx, tmx_text(sheet_layout(s.kind(), s.horizontal_radix()), t, file_stem(ts.name) + ".tsx",
                                    ts.tile_px));
}

}  // namespace

std::string check_pair_fill(const std::vector<int>& map, int rows, int cols, bool torus,
                            const std::vector<std::array<int, 3>>& pairs, int tiles) {
  if (map.size() != std::size_t(rows) * std::size_t(cols)) return "the map's size is wrong";
  std::vector<bool> allowed(4 * std::size_t(tiles) * std::size_t(tiles), false);
  for (const auto& [d, a, b] : pairs)
    if (d >= 0 && d < 4 && a >= 0 && a < tiles && b >= 0 && b < tiles)
      allowed[(std::size_t(d) * std::size_t(tiles) + std::size_t(a)) * std::size_t(tiles) + std::size_t(b)] = true;
  struct Lookup {
    const std::vector<bool>& v;
    std::size_t n;
    std::size_t count(const std::array<int, 3>& p) const {
      return v[(std::size_t(p[0]) * n + std::size_t(p[1])) * n + std::size_t(p[2])] ? 1 : 0;
    }
  } ok{allowed, std::size_t(tiles)};
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) {
      const int a = map[std::size_t(r) * std::size_t(cols) + std::size_t(c)];
      if (a < 0 || a >= tiles) return fmt::format("cell ({},{}) holds no tile", r, c);
      if (c + 1 < cols || torus) {
        const int b = map[std::size_t(r) * std::size_t(cols) + std::size_t((c + 1) % cols)];
        if (!ok.count({1, a, b}) || !ok.count({3, b, a}))
          return fmt::format("cells ({},{}) and ({},{}): tiles {} and {} may not sit side by side", r, c, r,
                             (c + 1) % cols, a, b);
      }
      if (r + 1 < rows || torus) {
        const int b = map[std::size_t((r + 1) % rows) * std::size_t(cols) + std::size_t(c)];
        if (!ok.count({2, a, b}) || !ok.count({0, b, a}))
          return fmt::format("cells ({},{}) and ({},{}): tile {} may not sit above {}", r, c, (r + 1) % rows, c, a, b);
      }
    }
  return "";
}

bool is_tmx(const std::string& path) { return ends_with(path, ".tmx"); }

FillJobOutcome run_fill(const FillJobRequest& req_in) {
  FillJobRequest req = req_in;
  const bool painted = is_tmx(req.cells);
  if (painted && req.width == 0 && req.height == 0) {  // the size of the painted map
    const PaintedMap m = read_painted_map(req.cells);
    req.width = m.width, req.height = m.height;
  }
  if (req.width < 1 || req.height < 1)
    throw RequestError("size", painted || req.width || req.height ? "`size` must be at least 1x1"
                                                                  : "`size` is needed unless `cells` is a Tiled map (.tmx)");
  LoadedSet ls = load_set(req);
  for (const auto& [name, w] : req.weights) {
    const std::vector<int> ts = tiles_named(ls, name);
    if (ts.empty()) throw RequestError("weights", fmt::format("`weights`: \"{}\" is no tile of the set", name.substr(0, 32)));
    for (int t : ts) ls.weights[std::size_t(t)] = w;
  }
  FillJobOutcome o;
  FillMapRequest mr;
  mr.rules = make_rules(ls);
  mr.rows = req.height;
  mr.cols = req.width;
  mr.torus = req.torus;
  std::optional<PaintedCells> pc;
  if (painted) {
    pc = read_painted_cells(ls, req, req.height, req.width, o.fixed);
    mr.fixed = pc->cells;
  } else if (!req.cells.empty()) {
    mr.fixed = read_cells(ls, req.cells, req.height, req.width, o.fixed);
  }
  o.rows = req.height, o.cols = req.width;
  mr.block = req.block;
  mr.cover = req.cover;
  mr.order = req.order;
  mr.dives = req.dives;
  mr.run = req.run;
  o.source = ls.source;
  o.names = ls.names;
  o.weights = ls.weights;
  if (!req.out_cnf.empty()) {
    write_file_atomic(req.out_cnf, fill_cnf_text(mr, &o.cnf_variables, &o.cnf_clauses));
    o.cnf = req.out_cnf;
    return o;
  }
  if (req.sat && (!req.run.checkpoint_path.empty() || !req.run.resume_path.empty()))
    throw RequestError("sat", "`sat` runs cadical once over the whole map: it takes no `checkpoint` or `resume`");
  o.fill = req.sat ? fill_by_sat(mr) : fill_map(mr);
  if (!o.fill.found) return o;
  const std::vector<int>& map = o.fill.map;
  // the independent check, then the fixed cells
  if (ls.wfc) {
    const std::string err = check_pair_fill(map, req.height, req.width, req.torus, ls.wfc->pairs, int(ls.names.size()));
    if (!err.empty()) throw std::logic_error("the fill is not valid: " + err);
  } else {
    const ValidationReport rep = validate(as_tiling(*ls.set, map, req.height, req.width, req.torus), &*ls.set);
    if (!rep.valid) throw std::logic_error("the fill is not valid: " + (rep.errors.empty() ? "" : rep.errors[0]));
  }
  for (std::size_t i = 0; i < mr.fixed.size(); ++i)
    if (mr.fixed[i] >= 0 && map[i] != mr.fixed[i]) throw std::logic_error("the fill changed a fixed cell");
  o.counts.assign(ls.names.size(), 0);
  for (int t : map) ++o.counts[std::size_t(t)];
  if (req.cover)
    for (std::size_t t = 0; t < o.counts.size(); ++t)
      if (o.counts[t] == 0) throw std::logic_error("the sheet misses tile " + ls.names[t]);
  o.valid = true;
  if (pc && !req.out_tiled.empty())  // before any file is written: every filled tile has a gid to show it
    for (int t : map)
      if (pc->gid_of_tile[std::size_t(t)] == 0)
        throw InputError(fmt::format("{}: tile {} of the fill has no tile in the map's tilesets", req.cells,
                                     ls.names[std::size_t(t)]));
  // outputs, each written atomically
  if (!req.out_png.empty()) {
    if (ls.wfc) {
      write_png(req.out_png, wfc_picture(*ls.wfc, map, req.height, req.width));
    } else if (ls.source == "blob") {
      write_png(req.out_png, blob_picture(map, req.height, req.width, req.tile_px - req.tile_px % 3));
    } else {
      const atlas::RenderOptions opt{req.tile_px, false};
      atlas::check_tiling_picture(req.height, req.width, opt);
      atlas::write_picture(atlas::draw_tiling(as_tiling(*ls.set, map, req.height, req.width, req.torus), opt), req.out_png);
    }
    o.png = req.out_png;
  }
  if (!req.out_json.empty()) {
    nlohmann::json j = {{"set", req.set}, {"subset", req.subset}, {"rows", req.height}, {"cols", req.width},
                        {"torus", req.torus}, {"seed", req.run.seed}, {"names", ls.names}};
    nlohmann::json rows = nlohmann::json::array();
    for (int r = 0; r < req.height; ++r)
      rows.push_back(std::vector<int>(map.begin() + std::ptrdiff_t(r) * req.width, map.begin() + std::ptrdiff_t(r + 1) * req.width));
    j["cells"] = std::move(rows);
    write_file_atomic(req.out_json, j.dump() + "\n");
    o.json = req.out_json;
  }
  if (!req.out_tiled.empty()) {
    if (pc)
      write_painted_tmx(*pc, req, map, ls.names, o);
    else
      write_tiled(ls, req, map, o);
  }
  return o;
}

}  // namespace tilekit::tilemap
