// What `texture render` and `texture preview` share: the texture source and the view.
#include <fmt/format.h>

#include <cerrno>
#include <cstdlib>

#include "base/error.hpp"
#include "base/parse.hpp"
#include "cli/cmd_texture.hpp"
#include "cli/numeric_flags.hpp"
#include "render/anisotropic.hpp"
#include "texture/exemplar.hpp"

namespace tilekit::cli {

void add_source_options(CLI::App* cmd, SourceArgs& a) {
  cmd->add_option("--method", a.method,
                  "tiles (the atlas, thesis 5.4), hex (Mikkelsen 2022 hex tiling) or hpn (Heitz & Neyret 2018 "
                  "histogram-preserving blending); hex and hpn sample --exemplar directly")
      ->capture_default_str();
  cmd->add_option("--atlas", a.atlas, "Atlas PNG (or its .json) written by `tilekit texture atlas`");
  cmd->add_option("--exemplar", a.exemplar,
                  "Exemplar of hex and hpn (PNG or JPEG, or a fetched real texture by name: brick, grass, gravel)");
  cmd->add_option("--cell-px", a.cell_px,
                  "hex/hpn: triangle side in texels (default: the papers' scale, min(width, height) / (2 sqrt 3))")
      ->check(positive_number());
  cmd->add_option("--hash", a.hash, "Lattice hash of the tiling and of the patch centres: perm or long-period")
      ->capture_default_str();
  cmd->add_option("--seed", a.seed, "Seed of that hash")->capture_default_str();
  cmd->add_option("--aniso", a.aniso, "Most anisotropic taps per fetch, 1 (trilinear) to 16")
      ->check(CLI::Range(1, kMaxAnisotropy))
      ->capture_default_str();
  cmd->add_option("--filter", a.filter,
                  "tiles: taps (each anisotropic tap through the tiling, textureLod) or hardware (one textureGrad "
                  "with the virtual texture's gradients, the sampler's own anisotropic taps in the atlas)")
      ->check(CLI::IsMember({"taps", "hardware"}))
      ->capture_default_str();
}

std::unique_ptr<LoadedSource> load_source(const SourceArgs& a) {
  auto s = std::make_unique<LoadedSource>();
  s->source.method = parse_render_method(a.method);
  s->options.hash = parse_hash_kind(a.hash);
  s->options.seed = a.seed;
  s->options.max_aniso = a.aniso;
  s->options.hardware_filter = a.filter == "hardware";
  s->source.hardware_filter = s->options.hardware_filter;
  const bool tiles = s->source.method == RenderMethod::Tiles;
  if (tiles && a.atlas.empty()) throw InputError("--method tiles needs --atlas (written by `tilekit texture atlas`)");
  if (!tiles && a.exemplar.empty())
    throw InputError(fmt::format("--method {} needs --exemplar (the texture it samples directly)", a.method));
  if (!(a.cell_px >= 0)) throw InputError(fmt::format("--cell-px must be positive, got {}", a.cell_px));
  if (!a.atlas.empty()) s->atlas = read_texture_atlas(a.atlas);
  if (!a.exemplar.empty()) {
    const Exemplar e = load_exemplar(a.exemplar);
    s->exemplar = make_exemplar_surface(e.image, e.name, a.cell_px);
  }
  s->source.atlas = s->atlas ? &*s->atlas : nullptr;
  s->source.exemplar = s->exemplar ? &*s->exemplar : nullptr;
  return s;
}

nlohmann::json source_json(const LoadedSource& s) {
  nlohmann::json j = {{"method", render_method_name(s.source.method)},
                      {"hash", hash_kind_name(s.options.hash)},
                      {"seed", s.options.seed},
                      {"aniso", s.options.max_aniso},
                      {"filter", s.options.hardware_filter ? "hardware" : "taps"},
                      {"memory_bytes", s.source.memory_bytes()}};
  if (s.atlas) {
    j["kind"] = kind_name(s.atlas->lookup.kind);
    j["colors"] = s.atlas->lookup.colours;
    j["tile_px"] = s.atlas->tile_px;
  }
  if (s.exemplar) {
    j["exemplar"] = s.exemplar->name;
    j["cell_px"] = s.exemplar->cell_px;
  }
  return j;
}

View parse_view(const std::string& size, double scale, const std::string& origin, double tilt) {
  View v;
  const Dimensions d = parse_dimensions(size, kMaxViewSide, std::int64_t(kMaxViewSide) * kMaxViewSide, "--size WxH");
  v.width = int(d.first);
  v.height = int(d.second);
  if (!origin.empty()) {
    // Two decimal numbers separated by a comma, nothing else.
    const char* p = origin.c_str();
    char* end = nullptr;
    errno = 0;
    v.origin_u = std::strtod(p, &end);
    const bool first = end != p && *end == ',';
    char* end2 = nullptr;
    if (first) v.origin_v = std::strtod(end + 1, &end2);
    if (!first || end2 == end + 1 || *end2 != '\0' || errno == ERANGE)
      throw InputError(fmt::format("--origin must be U,V in texels, got '{}'", origin));
  }
  v.scale = scale;
  v.tilt = tilt;
  return v;
}

}  // namespace tilekit::cli
