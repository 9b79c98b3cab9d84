// tilekit tile --set SET --algo ALGO --size WxH [--seed S] [--hash perm|long-period] [--map FILE]
//              [--out FILE(.json|.svg|.png)] [--borders] [--tile-size PX]
// Generates a tiling with one of the algorithms of thesis ch. 3 / Schloemer & Deussen 2010 and
// always checks it with the independent validator.
#include <fmt/format.h>

#include <chrono>
#include <set>

#include "base/atomic_file.hpp"
#include "atlas/render.hpp"
#include "base/parse.hpp"
#include "cli/command.hpp"
#include "base/error.hpp"
#include "tilesets/tile_set_io.hpp"
#include "tiling/tiling_algorithms.hpp"
#include "tilesets/validator.hpp"

namespace tilekit::cli {

namespace {

struct TileArgs {
  std::string set, algo, size, hash = "long-period", map, out;
  std::uint64_t seed = 1;
  bool borders = false;
  int tile_px = 0;
};

std::pair<int, int> parse_size(const std::string& s) {
  const Dimensions d = parse_dimensions(s, 65536, std::int64_t(1) << 24, "--size WxH");
  check_tiling_size(d.second, d.first);
  return {int(d.first), int(d.second)};
}

void check_out_path(const std::string& out) {
  if (!out.empty() && !out.ends_with(".json") && !atlas::is_picture_path(out))
    throw InputError(fmt::format("{}: unknown output format (expected a .json, .svg or .png file name)", out));
}

void run_tile(const TileArgs& a, const Context& ctx) {
  check_out_path(a.out);
  TilingRequest req;
  std::tie(req.cols, req.rows) = parse_size(a.size);
  req.algo = parse_tiling_algo(a.algo);
  req.hash = parse_hash_kind(a.hash);
  req.seed = a.seed;
  if (atlas::is_picture_path(a.out)) atlas::check_tiling_picture(req.rows, req.cols, {a.tile_px, a.borders});
  if (!a.map.empty()) {
    if (req.algo != TilingAlgo::Controlled) throw InputError("--map only applies to --algo controlled");
    req.map = read_probability_map(a.map);
  }
  const TileSet set = resolve_tile_set(a.set);
  const auto start = std::chrono::steady_clock::now();
  const Tiling t = generate_tiling(set, req);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const ValidationReport rep = validate(t, &set);
  const std::size_t distinct = std::set<TileIndex>(t.cells.begin(), t.cells.end()).size();
  if (!a.out.empty()) {
    if (a.out.ends_with(".json"))
      write_file_atomic(a.out, tiling_to_json(t).dump() + "\n");
    else
      atlas::write_picture(atlas::draw_tiling(t, {a.tile_px, a.borders}), a.out);
  }
  nlohmann::json j = {{"valid", rep.valid},      {"rows", t.rows},
                      {"cols", t.cols},          {"distinct_tiles", distinct},
                      {"seconds", seconds},      {"set", set.name()},
                      {"set_tiles", set.size()}, {"kind", std::string(kind_name(t.kind))},
                      {"colors", set.colours()}, {"algo", tiling_algo_name(req.algo)},
                      {"seed", req.seed}};
  if (req.algo != TilingAlgo::Scanline && req.algo != TilingAlgo::Halton) j["hash"] = hash_kind_name(req.hash);
  if (!a.out.empty()) j["out"] = a.out;
  if (!rep.valid) j["errors"] = rep.errors;
  emit(ctx, j, [&] {
    fmt::print("{} {} tiling of {}: {}x{} tiles, {} distinct of {}, {} ({:.3f} s){}\n", tiling_algo_name(req.algo),
               kind_name(t.kind), set.name(), t.cols, t.rows, distinct, set.size(), rep.valid ? "valid" : "INVALID",
               seconds, a.out.empty() ? "" : " -> " + a.out);
    for (const auto& e : rep.errors) fmt::print("  {}\n", e);
  });
  if (!rep.valid) throw Exit{1};
}

}  // namespace

void add_tile_command(CLI::App& app, Context& ctx) {
  auto* cmd = app.add_subcommand("tile", "Generate a tiling (scanline, direct, Halton or controlled) and validate it");
  auto a = std::make_shared<TileArgs>();
  cmd->add_option("--set", a->set, "Tile set: built-in name (see `tileset list`) or tile-set file")->required();
  cmd->add_option("--algo", a->algo,
                  "scanline | direct | direct-edge | direct-compact | halton | controlled "
                  "(thesis ch. 3; Schloemer & Deussen 2010)")
      ->required();
  cmd->add_option("--size", a->size, "Width x height in tiles, e.g. 16x16")->required();
  cmd->add_option("--seed", a->seed, "Random seed (hash tables, scanline choices); default 1")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--hash", a->hash, "Hash of the direct and controlled algorithms: perm | long-period (default)");
  cmd->add_option("--map", a->map,
                  "Colour probability map (JSON {colors, rows, cols, p}) for --algo controlled; "
                  "default: a left-to-right ramp through the colours");
  cmd->add_option("--out", a->out, "Write the tiling: FILE.json (tiling file), FILE.svg or FILE.png (picture)");
  cmd->add_flag("--borders", a->borders, "Draw tile borders in pictures");
  cmd->add_option("--tile-size", a->tile_px, "Pixels per tile in pictures (default: chosen from the size)")
      ->check(CLI::Range(1, 512));
  add_json_flag(cmd, ctx);
  cmd->callback([a, &ctx] { run_tile(*a, ctx); });
}

}  // namespace tilekit::cli
