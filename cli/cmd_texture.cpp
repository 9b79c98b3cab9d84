// tilekit texture tiles|atlas|render: texture tiles from an exemplar (thesis sec. 5.3), atlases
// laid out by packings with mip chains (5.4), and renders of the infinite virtual texture on
// the CPU or through GLSL (headless EGL, Mesa llvmpipe).
#include "cli/cmd_texture.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "atlas/lookup.hpp"
#include "base/error.hpp"
#include "base/json_input.hpp"
#include "cli/command.hpp"
#include "cli/numeric_flags.hpp"
#include "cli/packing_lookup.hpp"
#include "cli/run_options.hpp"
#include "image/image.hpp"
#include "render/glsl_sampler.hpp"
#include "texture/material.hpp"
#include "texture/texture_atlas.hpp"
#include "texture/tile_synthesis.hpp"

namespace tilekit::cli {

namespace {

namespace fs = std::filesystem;

HashKind hash_option(const std::string& name) {
  return parse_hash_kind(name);
}

struct TilesArgs {
  std::string exemplar, kind = "corner", out, period = "auto", perspective = "auto", tile_px = "auto";
  SynthesisOptions synthesis;  // kind, threads, seed, progress and keep_period come from the fields here
  RunOptions run = [] {
    RunOptions r;
    r.seed = SynthesisOptions{}.seed;
    return r;
  }();
  bool tileable = false, quiet = false, coords = false, thin_bands = false, wide_bands = false;
  std::vector<std::string> maps;
  std::string map_cost = "all";
  double albedo_weight = 1;
};

// The exemplar at its own depth (a 16-bit PNG or TIFF keeps 16 bits), one copy of a torus. A
// float exemplar is refused: the synthesis reads 8 bits, which would clamp float data to 0..1.
Image exemplar_at_depth(const std::string& path_or_name, const Exemplar& e) {
  std::error_code ec;
  if (fs::is_regular_file(path_or_name, ec)) {
    Image img = read_image(path_or_name, 4, true);
    if (img.is_float())
      throw InputError(
          fmt::format("{}: a float exemplar (OpenEXR or float TIFF); give float data as --map "
                      "NAME=FILE:linear beside an 8- or 16-bit exemplar",
                      path_or_name));
    if (img.width == (e.wrap_w ? e.wrap_w : e.width()) && img.height == (e.wrap_h ? e.wrap_h : e.height())) return img;
  }
  const int w = e.wrap_w ? e.wrap_w : e.width(), h = e.wrap_h ? e.wrap_h : e.height();
  Image img(w, h);
  for (int y = 0; y < h; ++y) std::copy_n(e.image.at(0, y), std::size_t(w) * 4, img.at(0, y));
  return img;
}

// A material set (texture/material.hpp): the synthesis on the albedo with every map's term in its
// seam costs (or the albedo alone: --map-cost albedo), every map's tiles copied at the recorded texels.
struct MaterialRun {
  std::vector<MaterialMap> maps;
  Image albedo;  // at its own depth
  nlohmann::json report = nlohmann::json::object();
};

TextureTileSet synthesize_material(const TilesArgs& a, const Exemplar& e, const SynthesisOptions& o, MaterialRun& m) {
  const int w = m.albedo.width, h = m.albedo.height;
  if (w > 65535 || h > 65535)
    throw InputError(fmt::format("{}: material sets take exemplars up to 65535 px a side", e.name));
  const bool tileable = e.wrap_w > 0;
  std::vector<std::pair<int, int>> sizes;
  for (const MaterialMap& map : m.maps) sizes.push_back({map.image.width, map.image.height});
  resize_maps(m.maps, w, h, tileable);
  for (std::size_t k = 0; k < m.maps.size(); ++k)
    if (m.maps[k].resized)
      fmt::print(stderr, "map {}: {}x{} resampled to the exemplar's {}x{} (bilinear{})\n", m.maps[k].name,
                 sizes[k].first, sizes[k].second, w, h, m.maps[k].space == ColourSpace::Normal ? ", renormalised" : "");
  SynthesisOptions so = o;
  so.record_coords = true;
  if (a.map_cost == "all" && !m.maps.empty()) {
    so.cost_maps = seam_cost_maps(m.maps);
    so.colour_weight = a.albedo_weight;
  }
  TextureTileSet s = synthesize_tiles(e, so);
  const Image albedo = map_as_sampled(m.albedo, tileable, s.perspective, s.exemplar_scale);
  s.tiles = transfer_tiles(s.coords, s.tile_px, albedo);
  if (s.sampled.width > 0) s.sampled = albedo.to_depth(8);
  nlohmann::json maps = nlohmann::json::array();
  for (std::size_t k = 0; k < m.maps.size(); ++k)
    maps.push_back({{"name", m.maps[k].name},
                    {"file", m.maps[k].file},
                    {"colour_space", std::string(colour_space_name(m.maps[k].space))},
                    {"weight", m.maps[k].weight},
                    {"bits", m.maps[k].image.depth},
                    {"size", {sizes[k].first, sizes[k].second}},
                    {"resampled", m.maps[k].resized},
                    {"folder", "maps/" + m.maps[k].name}});
  m.report = {{"maps", maps},
              {"map_cost", m.maps.empty() ? "albedo" : a.map_cost},
              {"albedo_weight", a.albedo_weight},
              {"bits", m.albedo.depth},
              {"exemplar_size", {w, h}},
              {"coords", "coords"}};
  return s;
}

void run_tiles(const TilesArgs& a, const Context& ctx) {
  SynthesisOptions o = a.synthesis;
  o.kind = a.kind == "wang" ? TileKind::Wang : TileKind::Corner;
  o.threads = a.run.resolved_threads();
  o.seed = a.run.seed;
  o.progress = !a.quiet;
  o.keep_period = a.period != "off";
  if (a.thin_bands && a.wide_bands) throw InputError("--thin-bands and --wide-bands: choose one");
  o.thin_bands = !a.wide_bands;                   // thin by default: less grid repetition on every texture measured
  if (a.period != "auto" && a.period != "off") {  // X,Y in pixels (0: none along that axis)
    double x = 0, y = 0;
    char tail = 0;
    if (std::sscanf(a.period.c_str(), "%lf,%lf%c", &x, &y, &tail) != 2 || !(x == 0 || (x >= 4 && x <= 4096)) ||
        !(y == 0 || (y >= 4 && y <= 4096)) || (x == 0 && y == 0))
      throw InputError(
          fmt::format("--period '{}': expected auto, off or X,Y in pixels (each 0 or 4..4096, not both 0)", a.period));
    o.period_override = {x, y};
  }
  o.rectify = a.perspective == "auto";
  std::string tile_text = a.tile_px;
  if (tile_text != "auto") {  // an integer, through the same strict parse as every numeric flag
    if (!cli::strict_number(tile_text, "INT").empty() || std::stoll(tile_text) < 0 || std::stoll(tile_text) > 1 << 20)
      throw InputError(fmt::format("--tile-px '{}': expected auto or an even number of pixels in 16..1024", a.tile_px));
    o.tile_px = int(std::stoll(tile_text));
  }
  const Exemplar e = load_exemplar(a.exemplar, a.tileable);
  nlohmann::json tile_choice = nullptr;
  if (tile_text == "auto") {  // from the feature scale (texture/exemplar.hpp)
    ExemplarPeriod p;
    if (o.keep_period) p = dominant_period(e);
    if (o.period_override[0] > 0 || o.period_override[1] > 0) p.x = o.period_override[0], p.y = o.period_override[1];
    const TileSizeChoice c = choose_tile_size(e, p);
    o.tile_px = c.tile_px;
    tile_choice = {{"tile_px", c.tile_px}, {"reason", c.reason}, {"feature_px", c.feature_px}, {"period", c.period}};
    if (!a.quiet) fmt::print(stderr, "texture tiles: --tile-px auto: {}\n", c.reason);
  }
  MaterialRun m;
  for (const std::string& spec : a.maps) m.maps.push_back(parse_material_map(spec));
  m.albedo = exemplar_at_depth(a.exemplar, e);
  const bool material = !m.maps.empty() || m.albedo.depth == 16 || a.coords;
  const TextureTileSet s = material ? synthesize_material(a, e, o, m) : synthesize_tiles(e, o);
  write_tile_set(s, a.out, e.name, [&](const std::string& dir, nlohmann::json& manifest) {
    if (!tile_choice.is_null()) manifest["tile_px_auto"] = tile_choice;
    if (!material) return;
    manifest.update(m.report);
    nlohmann::json base = manifest;
    base.erase("maps");
    const bool tileable = e.wrap_w > 0;
    for (const MaterialMap& map : m.maps) {
      nlohmann::json mj = base;
      mj["map"] = map.name;
      mj["file"] = map.file;
      write_map_tiles(
          (fs::path(dir) / "maps" / map.name).string(),
          transfer_tiles(s.coords, s.tile_px, map_as_sampled(map.image, tileable, s.perspective, s.exemplar_scale)),
          map.space, mj);
    }
    nlohmann::json cj = base;
    cj["files"] = "tile-NNNN.png: 16-bit, R = x and G = y of the exemplar texel (as sampled) each texel is a copy of";
    write_map_tiles((fs::path(dir) / "coords").string(), coordinate_tiles(s.coords, s.tile_px), ColourSpace::Linear,
                    cj);
  });
  nlohmann::json j = tile_set_json(s);
  if (material) j.update(m.report);
  if (!tile_choice.is_null()) j["tile_px_auto"] = tile_choice;
  if (const std::string why = o.keep_period ? structure_message(s.period) : ""; !why.empty())
    fmt::print(stderr, "texture tiles: {}\n", why);
  j["exemplar"] = e.name;
  j["tileable"] = e.wrap_w > 0;
  j["out"] = a.out;
  j["sheet"] = (fs::path(a.out) / "tileset.png").string();
  j["labels"] = (fs::path(a.out) / "labels").string();
  j["threads"] = o.threads;
  emit(ctx, j, [&] {
    if (a.quiet) return;
    fmt::print("{}: {} {} texture tiles over {} colours, {}x{} px, from {} ({}, {:.2f} s)\n", a.out, s.tiles.size(),
               a.kind, o.colours, o.tile_px, o.tile_px, e.name, s.method, s.seconds);
    fmt::print("boundary-cut error {:.1f} (first draw {:.1f}); picture of the set: {}\n", s.cut_error,
               s.cut_error_initial, j["sheet"].get<std::string>());
    if (s.perspective.applied)
      fmt::print(
          "photographed wall: rectified by its {} lines ({} of them, {:.3f} periods rms; spacing spread {:.2f})\n",
          s.perspective.axis == 0 ? "vertical" : "horizontal", s.perspective.lines, s.perspective.rms,
          s.perspective.spread);
    if (s.exemplar_scale[0] != 1 || s.exemplar_scale[1] != 1)
      fmt::print("periodic exemplar (period {:g} x {:g} px): resampled by {:.3f} x {:.3f} to whole periods per tile\n",
                 s.period.x, s.period.y, s.exemplar_scale[0], s.exemplar_scale[1]);
    for (const MaterialMap& map : m.maps)
      fmt::print("map {} ({}, {} bits): {}/maps/{}/\n", map.name, colour_space_name(map.space), map.image.depth, a.out,
                 map.name);
    if (material)
      fmt::print("texel coordinates (for `texture transfer`): {}/coords/; samples and cuts chosen on {}\n", a.out,
                 m.maps.empty() || a.map_cost == "albedo" ? "the albedo alone" : "all maps");
  });
}

void add_tiles(CLI::App& texture, Context& ctx) {
  auto* cmd =
      texture.add_subcommand("tiles", "Synthesise the complete corner or Wang texture tile set from an exemplar");
  auto a = std::make_shared<TilesArgs>();
  cmd->add_option("--exemplar", a->exemplar,
                  "Example texture (PNG, JPEG, TIFF, TGA, PPM; 16-bit PNG and TIFF keep 16 bits), or a fetched real "
                  "texture by name: brick, grass, gravel, "
                  "gimp-stone33, gimp-walnut, oa-dirt, oa-brick, oa-rock")
      ->required();
  cmd->add_flag("--tileable", a->tileable,
                "The exemplar repeats seamlessly (a pattern or game texture): sample it as a torus "
                "(the fetched gimp-* and oa-* textures are)");
  cmd->add_option("--kind", a->kind, "corner (Ng et al., thesis 5.3) or wang (Cohen et al. 2003)")
      ->check(CLI::IsMember({"corner", "wang"}))
      ->capture_default_str();
  cmd->add_option("--colors", a->synthesis.colours,
                  "Colours C: the complete set has C^4 tiles (4 recommended: grid repetition 0.02-0.03 with thin "
                  "bands on every irregular texture measured, against 0.03-0.04 for C = 3)")
      ->required();
  cmd->add_option("--tile-px", a->tile_px,
                  "Tile size in pixels (even, 16..1024), or auto (the default, by measurement: BENCHMARKS.md): from "
                  "the exemplar's feature scale (the fewest whole periods of 64 px or more, else two features "
                  "across by its luminance autocorrelation; 64..512), the choice and its reason on stderr and in "
                  "tiles.json")
      ->type_name("PX|auto")
      ->capture_default_str();
  cmd->add_option("--out", a->out, "Folder for tile-NNNN.png (by tile index), tiles.json, tileset.png and labels/")
      ->required();
  add_run_options(cmd, RunOptionFlags::Threads | RunOptionFlags::Seed, a->run);
  cmd->add_option("--search", a->synthesis.search,
                  "Candidate shared samples per sample and round (0: the first random draw, no search)")
      ->capture_default_str();
  cmd->add_option("--centre-candidates", a->synthesis.centre_candidates, "Centre patches scored per tile")
      ->capture_default_str();
  cmd->add_option("--centre-cuts", a->synthesis.centre_cuts, "Of those, how many get the full graph cut")
      ->capture_default_str();
  cmd->add_flag("--thin-bands", a->thin_bands,
                "The default (BENCHMARKS.md, \"defaults by measurement\"): share fewer texels (margin 3n/64, a "
                "wide cut zone pulled to the centre): less grid repetition, but mip level 2 next to a border is no "
                "longer exact; a periodic exemplar keeps wide bands");
  cmd->add_flag("--wide-bands", a->wide_bands,
                "The bands before thin ones were the default (margin 5n/64): mip levels 0-2 exact next to a border, "
                "cuts a little less visible, more grid repetition");
  cmd->add_option("--period", a->period,
                  "auto: keep a periodic exemplar's structure (resample it to whole periods per tile, samples in "
                  "phase); off: never; X,Y: this period in pixels (0: none along that axis), e.g. brick courses "
                  "the detector missed")
      ->capture_default_str();
  cmd->add_option("--perspective", a->perspective,
                  "auto: rectify a photographed periodic exemplar whose lines converge (fit the homography that "
                  "makes them parallel and equally spaced) before keeping its period; off: never")
      ->check(CLI::IsMember({"auto", "off"}))
      ->capture_default_str();
  cmd->add_option("--map", a->maps,
                  "Another map of the exemplar's surface, NAME=FILE[:ROLE[:WEIGHT]] (any number): ROLE srgb (colour), "
                  "linear (data: roughness, height; the default) or normal (tangent-space; the default for a map "
                  "called normal); tiles in DIR/maps/NAME/, aligned texel for texel with the exemplar's. FILE: PNG, "
                  "JPEG, TIFF or OpenEXR; 16-bit PNG and TIFF keep 16 bits (16-bit PNG tiles), float TIFF and "
                  "OpenEXR stay float (OpenEXR tiles; linear or normal only)")
      ->type_name("NAME=FILE[:ROLE[:WEIGHT]]");
  cmd->add_option("--map-cost", a->map_cost,
                  "all: the seam costs of samples and cuts add each map's term (WEIGHT x its step in units of its "
                  "mean step; normals as vectors) to the exemplar's; albedo: the exemplar alone")
      ->check(CLI::IsMember({"all", "albedo"}))
      ->capture_default_str();
  cmd->add_option("--albedo-weight", a->albedo_weight,
                  "With --map-cost all, the weight of the exemplar's own term in the seam costs (each map's is its "
                  "WEIGHT, default 1)")
      ->check(CLI::Range(0.0, 1000.0))
      ->capture_default_str();
  cmd->add_flag("--coords", a->coords,
                "Write DIR/coords/ (the exemplar texel of every tile texel) without --map, for `texture transfer`");
  cmd->add_flag("--quiet", a->quiet, "No progress output on stderr and no summary on stdout");
  add_json_flag(cmd, ctx);
  cmd->callback([a, &ctx] { run_tiles(*a, ctx); });
}

struct AtlasArgs {
  std::string dir, out, db, hash = "long-period", color_space;
  std::uint64_t seed = 1;
  bool no_db = false, power_of_two = false, no_toksvig = false;
};

void run_atlas(const AtlasArgs& a, const Context& ctx) {
  const TileSetManifest m = read_tile_set_manifest(a.dir);
  const TileKind kind = m.kind;
  // The constructed (or reference) packing unless a database is named, so that the atlas of a tile
  // set depends on nothing but the set: never on what the user's own database holds.
  const AtlasLookup lookup =
      a.db.empty() || a.no_db ? atlas_lookup(kind, m.colours) : lookup_with_database(kind, m.colours, a.db);
  // `--out` may name a folder that does not exist yet, as `texture tiles --out` may.
  if (const fs::path parent = fs::path(a.out).parent_path(); !parent.empty()) {
    std::error_code ec;
    fs::create_directories(parent, ec);
    if (ec) throw InputError(fmt::format("{}: cannot create the folder ({})", parent.string(), ec.message()));
  }
  // The tile set's colour space (tiles.json), unless --color-space says otherwise.
  ColourSpace space = m.colour_space;
  if (!a.color_space.empty()) parse_colour_space(a.color_space, space);  // checked by IsMember
  TextureAtlas atlas = build_texture_atlas(lookup, a.dir, space);
  if (a.power_of_two) atlas = resample_to_power_of_two(atlas);
  const RenderOptions ro{hash_option(a.hash), a.seed, 1, false};
  // The sampler in the other languages, beside atlas.glsl (render/shader_languages.hpp).
  const auto shaders_of = [&](const TextureAtlas& at) {
    std::vector<std::pair<std::string, std::string>> shaders;
    for (const ShaderLanguage l : {ShaderLanguage::GlslVulkan, ShaderLanguage::Hlsl, ShaderLanguage::Wgsl})
      shaders.emplace_back(shader_language_extension(l), glsl_sampler_file(at, ro, l));
    return shaders;
  };
  // The maps of a material set (DIR/maps/NAME, `texture tiles --map`) and its texel coordinates,
  // atlased the same way beside it: STEM-NAME.png (and its mips, manifest, header, GLSL).
  struct MapAtlas {
    std::string name;
    TextureAtlas atlas;
  };
  std::vector<MapAtlas> map_atlases;
  std::error_code ec;
  std::vector<fs::path> map_dirs;
  if (fs::is_directory(fs::path(a.dir) / "maps", ec))
    for (const auto& entry : fs::directory_iterator(fs::path(a.dir) / "maps", ec))
      if (entry.is_directory(ec) && fs::exists(entry.path() / "tiles.json", ec)) map_dirs.push_back(entry.path());
  if (fs::exists(fs::path(a.dir) / "coords" / "tiles.json", ec)) map_dirs.push_back(fs::path(a.dir) / "coords");
  std::sort(map_dirs.begin(), map_dirs.end());
  for (const fs::path& d : map_dirs) {
    const TileSetManifest mm = read_tile_set_manifest(d.string());
    if (mm.kind != m.kind || mm.colours != m.colours)
      throw InputError(fmt::format("{}: a {} set over {} colours beside a {} set over {}", d.string(),
                                   kind_name(mm.kind), mm.colours, kind_name(m.kind), m.colours));
    TextureAtlas ma = build_texture_atlas(lookup, d.string(), mm.colour_space);
    if (a.power_of_two) ma = resample_to_power_of_two(ma);
    map_atlases.push_back({d.filename().string(), std::move(ma)});
  }
  // Toksvig (texture/mipmap.hpp, toksvig_chain): the length the normal map's mips lose is folded
  // into the mips of the map called roughness, unless --no-toksvig.
  std::string toksvig_from;
  const auto named = [&](const std::string& name) {
    return std::find_if(map_atlases.begin(), map_atlases.end(), [&](const MapAtlas& ma) { return ma.name == name; });
  };
  if (const auto rough = named("roughness"); !a.no_toksvig && rough != map_atlases.end()) {
    auto normal = named("normal");
    if (normal == map_atlases.end() || normal->atlas.colour_space != ColourSpace::Normal)
      normal = std::find_if(map_atlases.begin(), map_atlases.end(),
                            [](const MapAtlas& ma) { return ma.atlas.colour_space == ColourSpace::Normal; });
    if (normal != map_atlases.end() && rough->atlas.colour_space != ColourSpace::Normal) {
      std::vector<Image> chain = toksvig_chain(rough->atlas.levels[0], normal->atlas.levels, MipEdge::Wrap);
      if (chain.size() == rough->atlas.levels.size()) {
        rough->atlas.levels = std::move(chain);
        toksvig_from = normal->name;
      }
    }
  }
  const AtlasFiles f = write_texture_atlas(atlas, a.out, glsl_sampler_file(atlas, ro), shaders_of(atlas));
  nlohmann::json maps = nlohmann::json::object();
  for (const MapAtlas& ma : map_atlases) {
    const AtlasFiles mf =
        write_texture_atlas(ma.atlas, atlas_stem(a.out) + "-" + ma.name + ".png", glsl_sampler_file(ma.atlas, ro),
                            shaders_of(ma.atlas));
    maps[ma.name] = {{"out", mf.levels[0]},
                     {"ktx2", mf.ktx2},
                     {"manifest", mf.manifest},
                     {"colour_space", std::string(colour_space_name(ma.atlas.colour_space))},
                     {"bits", ma.atlas.levels[0].depth}};
    if (ma.name == "roughness")
      maps[ma.name]["toksvig"] = toksvig_from.empty() ? nullptr : nlohmann::json(toksvig_from);
  }
  nlohmann::json j = {{"out", f.levels[0]},
                      {"levels", f.levels},
                      {"ktx2", f.ktx2},
                      {"manifest", f.manifest},
                      {"header", f.header},
                      {"glsl", f.glsl},
                      {"shaders", f.shaders},
                      {"kind", std::string(kind_name(kind))},
                      {"colors", lookup.colours},
                      {"rows", lookup.rows},
                      {"cols", lookup.cols},
                      {"tile_px", atlas.tile_px},
                      {"texels_per_tile", atlas_texels_per_tile(atlas)},
                      {"memory_bytes", RenderSource{RenderMethod::Tiles, &atlas, nullptr}.memory_bytes()},
                      {"width", atlas.levels[0].width},
                      {"height", atlas.levels[0].height},
                      {"source", lookup.source},
                      {"how", lookup.how},
                      {"colour_space", std::string(colour_space_name(atlas.colour_space))},
                      {"bits", atlas.levels[0].depth},
                      {"maps", maps}};
  emit(ctx, j, [&] {
    fmt::print(
        "{}: {}x{} atlas of {} {}-pixel tiles laid out by the {} packing ({}: {}), {} mip levels, {:.2f} MiB{}\n",
        f.levels[0], atlas.levels[0].width, atlas.levels[0].height, lookup.cells.size(), atlas.tile_px, kind_name(kind),
        lookup.source, lookup.how, f.levels.size(), j["memory_bytes"].get<double>() / (1 << 20),
        a.power_of_two ? fmt::format(" (resampled: {:.2f} texels a tile)", atlas_texels_per_tile(atlas)) : "");
    fmt::print(
        "KTX2 {} ({}, every level), manifest {}, C lookup {}, samplers {} (GLSL ES), {} (Vulkan GLSL), {} "
        "(HLSL), {} (WGSL)\n",
        f.ktx2, colour_space_name(atlas.colour_space), f.manifest, f.header, f.glsl, f.shaders[0], f.shaders[1], f.shaders[2]);
    fmt::print("colour space {}, {} bits\n", colour_space_name(atlas.colour_space), atlas.levels[0].depth);
    for (const auto& [name, mj] : maps.items())
      fmt::print("map {}: {} ({}, {} bits{})\n", name, mj["out"].get<std::string>(),
                 mj["colour_space"].get<std::string>(), mj["bits"].get<int>(),
                 name == "roughness" && !toksvig_from.empty()
                     ? fmt::format("; mips widened by the length map {}'s mips lose, Toksvig", toksvig_from)
                     : "");
  });
}

void add_atlas(CLI::App& texture, Context& ctx) {
  auto* cmd = texture.add_subcommand(
      "atlas", "Lay a texture tile set out as the packing from `atlas lookup`: atlas PNG, mip chain, lookup, GLSL");
  auto a = std::make_shared<AtlasArgs>();
  cmd->add_option("DIR", a->dir, "Folder written by `tilekit texture tiles`")->required();
  cmd->add_option("--out", a->out,
                  "Atlas PNG (its folder is made); atlas.mipK.png, atlas.ktx2, atlas.json, atlas.h and the samplers "
                  "atlas.glsl, atlas.vk.glsl, atlas.hlsl and atlas.wgsl go beside it, and atlas-NAME.png (and so on) "
                  "for every map of a material set (DIR/maps/NAME, DIR/coords)")
      ->required();
  cmd->add_flag("--no-toksvig", a->no_toksvig,
                "Keep a material's roughness mips plain averages (by default, when DIR/maps has a map called "
                "roughness and a normal map, the length the normal mips lose widens the roughness mips: Toksvig)");
  cmd->add_option("--color-space", a->color_space,
                  "How the levels are averaged and stored (default: the tile set's, from its tiles.json): srgb, "
                  "colour in linear light (atlas.ktx2 RGBA8 sRGB); linear, data such as roughness or height; normal, "
                  "tangent-space normals averaged as vectors (both RGBA8, or RGBA16 for 16-bit tiles, UNORM; float "
                  "tiles: OpenEXR levels and RGBA32 SFLOAT, never srgb)")
      ->check(CLI::IsMember({"srgb", "linear", "normal"}));
  cmd->add_option("--db", a->db,
                  "Results database to look for a stored packing in first (default: none, the constructed or "
                  "reference packing)");
  cmd->add_flag("--no-db", a->no_db, "Constructions only, no database (the default; kept for scripts)");
  cmd->add_flag("--power-of-two", a->power_of_two,
                "Resample level 0 to the nearest power of two per axis (area-weighted, wrapping: C = 3, 5, 6, 7 "
                "make 9, 25, 36, 49 tiles a side) and make the mips again; tiles then span fractional texels");
  cmd->add_option("--hash", a->hash, "Lattice hash of the tiling in atlas.glsl: perm or long-period")
      ->capture_default_str();
  cmd->add_option("--seed", a->seed, "Seed of that hash")->capture_default_str();
  add_json_flag(cmd, ctx);
  cmd->callback([a, &ctx] { run_atlas(*a, ctx); });
}

struct TransferArgs {
  std::string dir;
  std::vector<std::string> maps;
};

// A map made after the tiles: copied at the texels DIR/coords/ records, as `texture tiles --map`
// would have (resampled to the exemplar's grid, rectified and resampled as the samples saw it).
void run_transfer(const TransferArgs& a, const Context& ctx) {
  const fs::path coords_dir = fs::path(a.dir) / "coords";
  std::error_code ec;
  if (!fs::exists(coords_dir / "tiles.json", ec))
    throw InputError(fmt::format("{}: no texel coordinates (make the tiles with `texture tiles --map` or --coords)",
                                 coords_dir.string()));
  const nlohmann::json doc = read_json_file((fs::path(a.dir) / "tiles.json").string(), "texture tile-set manifest");
  const JsonIn j(doc, (fs::path(a.dir) / "tiles.json").string());
  const TileSetManifest m = read_tile_set_manifest(a.dir);
  const int tile_px = int(j.at("tile_px").integer(2, 1024));
  const JsonIn size = j.at("exemplar_size");
  const int w = int(size[0].integer(1, 65535)), h = int(size[1].integer(1, 65535));
  const bool tileable = j.boolean_or("tileable", false);
  std::array<double, 2> scale{1, 1};
  if (auto sc = j.find("exemplar_scale")) scale = {(*sc)[0].number(0.5, 2), (*sc)[1].number(0.5, 2)};
  PerspectiveFit fit;
  if (auto p = j.find("perspective"); p && p->boolean_or("applied", false)) {
    fit.applied = true;
    const JsonIn hm = p->at("homography");
    for (std::size_t k = 0; k < 9; ++k) fit.to_plane.m[k] = hm[k].number(-1e12, 1e12);
  }
  const std::size_t count = std::size_t(m.colours) * m.colours * m.colours * m.colours;
  std::vector<Image> coord_tiles(count);
  for (std::size_t t = 0; t < count; ++t) {
    coord_tiles[t] = read_image((coords_dir / fmt::format("tile-{:04d}.png", t)).string(), 4, true);
    if (coord_tiles[t].width != tile_px)
      throw InputError(fmt::format("{}: not {}x{} pixels", (coords_dir / fmt::format("tile-{:04d}.png", t)).string(),
                                   tile_px, tile_px));
  }
  const auto coords = coords_from_tiles(coord_tiles);
  nlohmann::json out = nlohmann::json::array();
  for (const std::string& spec : a.maps) {
    std::vector<MaterialMap> one{parse_material_map(spec)};
    const int w0 = one[0].image.width, h0 = one[0].image.height;
    resize_maps(one, w, h, tileable);
    if (one[0].resized)
      fmt::print(stderr, "map {}: {}x{} resampled to the exemplar's {}x{}\n", one[0].name, w0, h0, w, h);
    nlohmann::json mj = doc;
    mj.erase("maps");
    mj["map"] = one[0].name;
    mj["file"] = one[0].file;
    const std::string folder = (fs::path(a.dir) / "maps" / one[0].name).string();
    write_map_tiles(folder, transfer_tiles(coords, tile_px, map_as_sampled(one[0].image, tileable, fit, scale)),
                    one[0].space, mj);
    out.push_back({{"map", one[0].name},
                   {"folder", folder},
                   {"colour_space", std::string(colour_space_name(one[0].space))},
                   {"bits", one[0].image.depth},
                   {"resampled", one[0].resized}});
  }
  emit(ctx, {{"dir", a.dir}, {"maps", out}}, [&] {
    if (ctx.quiet) return;
    for (const auto& o : out)
      fmt::print("map {} ({}, {} bits): {}/\n", o["map"].get<std::string>(), o["colour_space"].get<std::string>(),
                 o["bits"].get<int>(), o["folder"].get<std::string>());
  });
}

void add_transfer(CLI::App& texture, Context& ctx) {
  auto* cmd = texture.add_subcommand(
      "transfer", "Carry further maps of the exemplar's surface onto a tile set by its texel coordinates (DIR/coords)");
  auto a = std::make_shared<TransferArgs>();
  cmd->add_option("DIR", a->dir, "Folder written by `texture tiles --map ...` or `texture tiles --coords`")->required();
  cmd->add_option("--map", a->maps,
                  "NAME=FILE[:ROLE] (any number; ROLE srgb, linear or normal): tiles in DIR/maps/NAME/")
      ->type_name("NAME=FILE[:ROLE]")
      ->required();
  add_json_flag(cmd, ctx);
  cmd->callback([a, &ctx] { run_transfer(*a, ctx); });
}

}  // namespace

void add_texture_commands(CLI::App& app, Context& ctx) {
  auto* texture = app.add_subcommand("texture", "Texture tiles from an exemplar, atlases from packings, renders");
  texture->require_subcommand(1);
  add_tiles(*texture, ctx);
  add_texture_terrain(*texture, ctx);
  add_atlas(*texture, ctx);
  add_transfer(*texture, ctx);
  add_texture_render(*texture, ctx);
  add_texture_preview(*texture, ctx);
  add_texture_analyze(*texture, ctx);
}

}  // namespace tilekit::cli
