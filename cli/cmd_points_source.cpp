// Where the point sets of `tilekit points` come from, and writing their pictures.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "atlas/atlas_image.hpp"
#include "base/error.hpp"
#include "base/resources.hpp"
#include "cli/cmd_points.hpp"
#include "cli/numeric_flags.hpp"
#include "points/generation_plan.hpp"
#include "points/reference_sets.hpp"
#include "points/tile_set_file.hpp"
#include "tilesets/tile_set.hpp"

namespace tilekit::cli::pts {

using namespace tilekit::points;

void add_source_options(CLI::App* cmd, SourceArgs& a) {
  cmd->add_option("--method", a.method, fmt::format("Where the points come from: {} (default corner)", kMethods));
  cmd->add_option("--tiles", a.tiles,
                  "Tile set: a file from `points tiles --out` (or db:ID) or `points recursive --out`; "
                  "default: built in memory from --colors/--points/--rho");
  cmd->add_option("--colors", a.colors, "Colours of a tile set built in memory (default 4)")->check(CLI::Range(1u, kMaxCompleteSetColours));
  cmd->add_option("--edge-colors", a.edge_colors, "corner: edge colours of a tile set built in memory (default 1)")
      ->check(CLI::Range(1, 16));
  cmd->add_option("--points", a.points,
                  "Points per tile of a set built in memory (default 1024 for corner, 64 for the others)")
      ->check(CLI::Range(1, 65536));
  cmd->add_option("--rho", a.rho,
                  "Relative radius of a tile set built in memory, or of Bridson's sampler (default 0.75)");
  cmd->add_option("--lloyd", a.lloyd, "Lloyd iterations at least per region of a set built in memory (default 0)")
      ->check(CLI::Range(0, 10000));
  cmd->add_option("--tile-seed", a.tile_seed, "Seed of a tile set built in memory (default 1)");
  cmd->add_option("--subdivision", a.subdivision, "recursive: sub-tiles per side of a set built in memory (default 2)")
      ->check(CLI::Range(2, 8));
  cmd->add_option("--levels", a.levels, "recursive: subdivision levels below the base tiles at most (default 20)")
      ->check(CLI::Range(0, 40));
  cmd->add_option("--base-tile", a.base_tile, "recursive: side of the base tiles (default: sqrt(2.5 N / density))")
      ->check(positive_number());
  cmd->add_option("--hash", a.hash, "Lattice hash of the direct stochastic tiling: perm | long-period (default)");
  cmd->add_option("--db", a.db, "Results database for --tiles db:ID (default: $TILEKIT_DB or the per-user one)");
}

Source::Source(const SourceArgs& a, int threads, bool progress) : a_(a) {
  parse_hash_kind(a.hash);  // fail early on a bad --hash
  if (a.method == "corner" || a.method == "wang" || a.method == "dual") {
    if (!a.tiles.empty()) {
      tiles_ = read_poisson_tiles(a.tiles, a.db);
      a_.method = method_name(tiles_->method);
    } else {
      PoissonTileParams p;
      p.method = parse_poisson_tile_method(a.method);
      p.colours = a.colors;
      p.edge_colours = a.edge_colors;
      p.points = a.points;
      p.rho = a.rho;
      p.lloyd = a.lloyd;
      p.seed = a.tile_seed;
      p.threads = threads;
      p.progress = progress;
      tiles_ = build_poisson_tiles(p);
    }
  } else if (a.method == "recursive") {
    if (!a.tiles.empty()) {
      recursive_ = read_recursive_tiles(a.tiles);
    } else {
      RecursiveTileParams p;
      p.points = a.points ? a.points : 64;
      p.subdivision = a.subdivision;
      p.seed = a.tile_seed;
      p.threads = threads;
      p.progress = progress;
      recursive_ = build_recursive_tiles(p);
    }
  } else if (a.method == "bridson") {
    if (!(a.rho > 0 && a.rho < 1)) throw InputError(fmt::format("--rho must be in (0, 1), got {}", a.rho));
  } else if (a.method != "white" && a.method != "grid" && a.method != "jitter") {
    throw InputError(fmt::format("unknown --method '{}' (expected {})", a.method, kMethods));
  }
  if (!a.tiles.empty() && !tiled()) throw InputError(fmt::format("--tiles does not apply to --method {}", a.method));
}

std::string Source::describe() const {
  if (tiles_)
    return fmt::format("{} Poisson disk tiles C={}{} N={} rho={}", a_.method, tiles_->colours,
                       tiles_->edge_colours > 1 ? fmt::format(" E={}", tiles_->edge_colours) : "", tiles_->points,
                       tiles_->rho);
  if (recursive_) return fmt::format("recursive Wang tiles N={} n={}", recursive_->points, recursive_->n);
  if (a_.method == "bridson") return fmt::format("Bridson dart throwing rho={}", a_.rho);
  return a_.method;
}

double Source::tile_size(double density) const {
  if (tiles_) return std::sqrt(double(tiles_->points) / density);
  if (recursive_) return a_.base_tile > 0 ? a_.base_tile : std::sqrt(2.5 * recursive_->points / density);
  return 0;
}

std::vector<double> Source::points(const Window& w, double density, std::uint64_t seed, int threads, std::int64_t period,
                                  bool torus, const DensityFunction* density_fn, ProgressReporter* progress) const {
  if (!(density > 0) || !std::isfinite(density))
    throw InputError(fmt::format("--density must be positive, got {}", density));
  require_window_memory(w, density, density_fn);
  const HashKind hash = parse_hash_kind(a_.hash);
  if (tiles_) {
    if (density_fn) throw InputError("a density function needs --method recursive (tile sets have constant density)");
    return PoissonTileGenerator(*tiles_, hash, seed, period).generate(w, density, threads, progress);
  }
  if (recursive_) {
    const auto constant = constant_density(density);
    return RecursiveGenerator(*recursive_, hash, seed, period)
        .generate(w, density_fn ? *density_fn : *constant, tile_size(density), a_.levels, threads);
  }
  if (density_fn) throw InputError("a density function needs --method recursive");
  if (a_.method == "bridson") return bridson_points(w, 2 * a_.rho * max_poisson_radius(density), seed, torus);
  if (a_.method == "white") return white_noise_points(w, std::uint64_t(std::llround(density * w.area())), seed);
  return grid_points(w, density, a_.method == "jitter", seed);
}

bool is_png(const std::string& path) {
  return path.ends_with(".png");
}
bool is_svg(const std::string& path) {
  return path.ends_with(".svg");
}

void check_extension(const std::string& path, const std::vector<std::string>& allowed, const char* flag) {
  if (path.empty()) return;
  for (const auto& ext : allowed)
    if (path.ends_with(ext)) return;
  throw InputError(fmt::format("{} {}: unknown file type (expected {})", flag, path, fmt::join(allowed, ", ")));
}

void write_image(const std::string& path, const Image& img) {
  if (!is_png(path)) throw InputError(fmt::format("{}: pictures are written as .png here", path));
  write_png(path, img);
}

}  // namespace tilekit::cli::pts
