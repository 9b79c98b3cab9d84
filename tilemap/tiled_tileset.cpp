#include "tilemap/tiled_tileset.hpp"

#include <fmt/format.h>

#include "atlas/render.hpp"
#include "base/error.hpp"
#include "tilemap/wang_id.hpp"
#include "tilemap/xml_text.hpp"
#include "tilesets/constructions.hpp"
#include "tilesets/validator.hpp"

namespace tilekit::tilemap {

TiledSheet sheet_layout(TileKind kind, std::uint32_t colours) {
  wang_type_name(kind);  // corner or Wang only
  if (colours < 1 || colours > kMaxSheetColours)
    throw RequestError(
        "colours", fmt::format("`colours` must be 1..{} for a Tiled sheet, got {}", kMaxSheetColours, colours));
  auto made = construct_packing(kind, colours);
  if (!made) throw InputError(fmt::format("no construction of a {} packing over {} colours", kind_name(kind), colours));
  const ValidationReport rep = validate(made->tiling);
  if (!rep.packing)
    throw std::logic_error(fmt::format("the constructed {} packing over {} colours is not a packing: {}",
                                       kind_name(kind), colours, rep.errors.empty() ? "" : rep.errors.front()));
  TiledSheet s{std::move(made->tiling), std::move(made->how), made->closed_form, {}};
  s.tile_id.assign(s.packing.cells.size(), 0);
  for (std::size_t k = 0; k < s.packing.cells.size(); ++k) s.tile_id[s.packing.cells[k]] = std::uint32_t(k);
  return s;
}

namespace {

std::string colour_name(std::uint32_t c, bool builtin) {
  static constexpr const char* names[] = {"red",    "yellow", "green", "cyan", "blue",  "magenta",
                                          "orange", "purple", "brown", "pink", "olive", "grey"};
  if (builtin && c < std::size(names)) return fmt::format("{} ({})", names[c], c);
  return fmt::format("colour {}", c);
}

// The one tile whose every corner (or edge) has colour c: thesis eq. 2.2 / 2.5 with all digits c.
TileIndex uniform_tile(std::uint32_t colours, Colour c) {
  return ((c * colours + c) * colours + c) * colours + c;
}

}  // namespace

std::string tsx_text(const TiledSheet& sheet, const TsxFile& f) {
  const Tiling& p = sheet.packing;
  const std::string name = xml_escape(f.name, "the tileset name");
  std::string s = fmt::format(
      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      "<tileset version=\"1.8\" name=\"{}\" tilewidth=\"{}\" tileheight=\"{}\" tilecount=\"{}\" columns=\"{}\">\n"
      " <image source=\"{}\" width=\"{}\" height=\"{}\"/>\n"
      " <wangsets>\n  <wangset name=\"{}\" type=\"{}\" tile=\"-1\">\n",
      name, f.tile_px, f.tile_px, p.cells.size(), p.cols, xml_escape(f.image, "the sheet's file name"),
      p.cols * f.tile_px, p.rows * f.tile_px, name, wang_type_name(p.kind));
  for (Colour c = 0; c < p.colours; ++c)
    s += fmt::format(
        "   <wangcolor name=\"{}\" color=\"{}\" tile=\"{}\" probability=\"1\"/>\n",
        c < f.colour_names.size() ? xml_escape(f.colour_names[c], "a colour name") : colour_name(c, f.builtin_colours),
        atlas::hex(c < f.colour_rgb.size() ? f.colour_rgb[c] : atlas::palette_colour(c)),
        sheet.tile_id[uniform_tile(p.colours, c)]);
  for (std::size_t k = 0; k < p.cells.size(); ++k)
    s += fmt::format("   <wangtile tileid=\"{}\" wangid=\"{}\"/>\n", k,
                     format_wang_id(wang_id_of(p.kind, p.colours, p.cells[k])));
  s += "  </wangset>\n </wangsets>\n</tileset>\n";
  return s;
}

std::string tmx_text(const TiledSheet& sheet, const Tiling& map, const std::string& tsx, int tile_px) {
  if (map.kind != sheet.packing.kind || map.colours != sheet.packing.colours || map.cv() != map.colours)
    throw InputError(fmt::format("a {} map over {} colours cannot use a {} tileset over {} colours",
                                 kind_name(map.kind), map.colours, kind_name(sheet.packing.kind),
                                 sheet.packing.colours));
  std::string s = fmt::format(
      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      "<map version=\"1.8\" orientation=\"orthogonal\" renderorder=\"right-down\" width=\"{0}\" height=\"{1}\" "
      "tilewidth=\"{2}\" tileheight=\"{2}\" infinite=\"0\" nextlayerid=\"2\" nextobjectid=\"1\">\n"
      " <tileset firstgid=\"1\" source=\"{3}\"/>\n"
      " <layer id=\"1\" name=\"tiles\" width=\"{0}\" height=\"{1}\">\n  <data encoding=\"csv\">\n",
      map.cols, map.rows, tile_px, xml_escape(tsx, "the tileset's file name"));
  s.reserve(s.size() + map.cells.size() * 5);
  for (int r = 0; r < map.rows; ++r) {
    for (int c = 0; c < map.cols; ++c) {
      const TileIndex t = map.at(r, c);
      if (t >= sheet.tile_id.size())
        throw InputError(fmt::format("map cell ({},{}): tile index {} is not in the tileset", r, c, t));
      s += fmt::format("{}", sheet.tile_id[t] + 1);  // gid = firstgid + tile id
      if (r + 1 < map.rows || c + 1 < map.cols) s += ',';
    }
    s += '\n';
  }
  s += "</data>\n </layer>\n</map>\n";
  return s;
}

}  // namespace tilekit::tilemap
