#include "render/preview.hpp"

#include <fmt/format.h>

#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string_view>

#include "base/hash.hpp"
#include "base/text_escape.hpp"
#include "render/baseline_samplers.hpp"
#include "render/glsl_sampler.hpp"
#include "render/preview_scripts.hpp"

namespace tilekit {

namespace {

std::string base64(std::string_view bytes) {
  static constexpr char kDigits[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::uint32_t a = std::uint8_t(bytes[i]), b = i + 1 < bytes.size() ? std::uint8_t(bytes[i + 1]) : 0,
                        c = i + 2 < bytes.size() ? std::uint8_t(bytes[i + 2]) : 0, v = a << 16 | b << 8 | c;
    out += kDigits[v >> 18];
    out += kDigits[(v >> 12) & 63];
    out += i + 1 < bytes.size() ? kDigits[(v >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? kDigits[v & 63] : '=';
  }
  return out;
}

// The half floats of a float image (as the GPU renderer uploads them), little-endian, base64.
std::string half_base64(const FloatImage& f) {
  std::string bytes;
  bytes.reserve(f.texels.size() * 2);
  for (float v : f.texels) {
    const std::uint16_t h = float_to_half(v);
    bytes += char(h & 255);
    bytes += char(h >> 8);
  }
  return base64(bytes);
}

// How the page recomputes a uniform hash table for any seed: the hash's seed is the page's seed
// passed through derive_seed with `streams` (DirectWangTiling and PatchHashes derive streams 1 and
// 2, DirectCornerTiling none); one permutation table (perm) or one per size with seed
// derive_seed(hash seed, i) (long-period, LongPeriodHash).
nlohmann::json recipe(const std::string& name, const ColourHash& h, std::vector<int> streams) {
  nlohmann::json sizes = nlohmann::json::array();
  for (const ColourHash::Component& c : h.components()) sizes.push_back(c.n);
  return {{"name", name}, {"kind", hash_kind_name(h.kind())}, {"streams", streams}, {"sizes", sizes}};
}

struct Page {
  nlohmann::json methods = nlohmann::json::object();
  std::string images;  // <img> elements holding the PNG levels
  int next_image = 0;

  nlohmann::json png_levels(const std::vector<Image>& levels) {
    nlohmann::json ids = nlohmann::json::array();
    for (const Image& l : levels) {
      const std::string id = fmt::format("tk-img-{}", next_image++);
      // A float atlas (OpenEXR levels) is shown as 8 bits, clamped to 0..1, as the renderers sample it.
      images += fmt::format("<img id=\"{}\" alt=\"\" src=\"data:image/png;base64,{}\">\n", id,
                            base64(encode_png(l.is_float() ? l.to_depth(8) : l)));
      ids.push_back(id);
    }
    return {{"format", "rgba8"}, {"levels", ids}};
  }
  static nlohmann::json half_levels(const std::vector<FloatImage>& levels, bool lut) {
    nlohmann::json data = nlohmann::json::array();
    for (const FloatImage& l : levels)
      data.push_back({{"width", l.width}, {"height", l.height}, {"data", half_base64(l)}});
    return {{"format", "rgba16f"}, {"levels", data}, {"clamp", lut}};
  }

  // `recipes`: the uniform tables (hex, hpn); `tiling`: how the page makes the tiles method's
  // look-up textures. `check`: the tables and the textures' FNV-1a for the page's own seed.
  void add(const RenderSource& src, const RenderOptions& o, nlohmann::json textures, nlohmann::json recipes,
           nlohmann::json tiling = nullptr) {
    nlohmann::json check = nlohmann::json::object();
    for (const auto& [name, values] : glsl_table_uniforms(src, o)) check[name] = values;
    for (const GlslTableTexture& t : glsl_table_textures(src, o))
      check[t.sampler] = std::to_string(
          StableHash().add(std::string_view(reinterpret_cast<const char*>(t.texels.data()), t.texels.size())).fnv());
    methods[render_method_name(src.method)] = {{"shader", glsl_fragment_shader(src, o, GlslMode::Texture)},
                                               {"unit", src.unit_px()},
                                               {"textures", std::move(textures)},
                                               {"tables", std::move(recipes)},
                                               {"tiling", std::move(tiling)},
                                               {"check", std::move(check)},
                                               {"memory_bytes", src.memory_bytes()}};
  }
};

// The page's script: the ports of the C++ tables and view (preview_tables.js), then the page
// (preview.js), both embedded at build time (preview_scripts.hpp).
std::string page_script() {
  std::string_view tables, page;
  for (const EmbeddedFile& f : preview_scripts()) {
    if (f.name == "preview_tables.js") tables = f.text;
    if (f.name == "preview.js") page = f.text;
  }
  if (tables.empty() || page.empty()) throw std::logic_error("the preview page's scripts are not embedded");
  std::string script = "\n";
  script += tables;
  script += "\n";
  script += page;
  return script;
}

}  // namespace

std::string preview_html(const TextureAtlas& atlas, const ExemplarSurface* exemplar, const RenderOptions& o) {
  Page page;
  const RenderSource tiles{RenderMethod::Tiles, &atlas, nullptr};
  {
    const DirectTiling tiling(atlas.lookup.kind, atlas.lookup.colours, o.hash, o.seed);
    const auto hashes = tiling.hashes();
    nlohmann::json recipes = nlohmann::json::array();
    if (hashes.size() == 1) {
      recipes.push_back(recipe("tk_lattice0_P", *hashes[0], {}));
    } else {
      recipes.push_back(recipe("tk_lattice0_P", *hashes[0], {1}));
      recipes.push_back(recipe("tk_lattice1_P", *hashes[1], {2}));
    }
    nlohmann::json spec = {
        {"kind", kind_name(atlas.lookup.kind)}, {"colors", atlas.lookup.colours}, {"tables", recipes}};
    if (glsl_tile_cell_texture(atlas.lookup, o.hash)) spec["positions"] = atlas.lookup.positions;
    nlohmann::json t = page.png_levels(atlas_levels_8bit(atlas));
    t["srgb"] = atlas.colour_space == ColourSpace::Srgb;  // uploaded as SRGB8_ALPHA8, as gl_renderer does
    t["unit"] = 0;
    t["sampler"] = "tk_atlas";
    page.add(tiles, o, nlohmann::json::array({t}), nlohmann::json::array(), spec);
  }
  if (exemplar) {
    const PatchHashes h(o.hash, o.seed);
    const nlohmann::json recipes = {recipe("tk_patch_x_P", h.x, {1}), recipe("tk_patch_y_P", h.y, {2})};
    nlohmann::json levels = page.png_levels(exemplar->levels);
    levels.update({{"unit", 0}, {"sampler", "tk_exemplar"}});
    page.add(RenderSource{RenderMethod::Hex, nullptr, exemplar}, o, nlohmann::json::array({levels}), recipes);
    nlohmann::json gaussian = Page::half_levels(exemplar->gaussian, false),
                   lut = Page::half_levels({exemplar->lut}, true);
    gaussian.update({{"unit", 0}, {"sampler", "tk_exemplar"}});
    lut.update({{"unit", 2}, {"sampler", "tk_lut"}});
    page.add(RenderSource{RenderMethod::Hpn, nullptr, exemplar}, o, nlohmann::json::array({gaussian, lut}), recipes);
  }
  const nlohmann::json data = {{"methods", page.methods},
                               {"vertex", glsl_vertex_shader()},
                               {"seed", std::to_string(o.seed)},
                               {"aniso", o.max_aniso}};
  std::string json = data.dump();
  // Inside <script>, "</script" would end the element early and "<!--" change how it is read:
  // every '<' (only ever inside a JSON string) as "\u003c", the same JSON string.
  for (std::size_t p = json.find('<'); p != std::string::npos; p = json.find('<', p + 6)) json.replace(p, 1, "\\u003c");
  const std::string title =
      fmt::format("tilekit preview: {} tiles over {} colours, {} px{}", kind_name(atlas.lookup.kind),
                  atlas.lookup.colours, atlas.tile_px, exemplar ? ", exemplar " + exemplar->name : "");
  std::string html = "<!doctype html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n<title>";
  html += html_escape(title);  // the exemplar's name is the user's (a file name): text, never markup
  html +=
      "</title>\n<style>\n"
      "html, body { margin: 0; height: 100%; overflow: hidden; background: #222; color: #eee; font: 13px sans-serif; "
      "}\n"
      "canvas { display: block; }\n"
      "#ui { position: fixed; left: 8px; top: 8px; padding: 8px; background: rgba(0, 0, 0, 0.7); border-radius: 4px; "
      "}\n"
      "#ui button.on { background: #6a6; }\n"
      "#msg { position: fixed; left: 8px; bottom: 8px; color: #f88; white-space: pre-wrap; }\n"
      "</style></head><body>\n<canvas id=\"view\"></canvas>\n<div id=\"ui\"><b>";
  html += html_escape(title);
  html +=
      "</b><br><span id=\"info\"></span><br>\n"
      "method <span id=\"methods\"></span> tilt <input id=\"tilt\" type=\"range\" min=\"0\" max=\"12\" step=\"0.1\">\n"
      "anisotropy <select id=\"aniso\"><option>1</option><option>2</option><option>4</option><option>8</option>"
      "<option>16</option></select> seed <input id=\"seed\" size=\"8\"><br>drag: pan, wheel: zoom</div>\n"
      "<pre id=\"msg\" hidden></pre>\n<div hidden>\n";
  html += page.images;
  html += "</div>\n<script type=\"application/json\" id=\"tk-data\">";
  html += json;
  html += "</script>\n<script>";
  html += page_script();
  html += "</script>\n</body></html>\n";
  return html;
}

}  // namespace tilekit
