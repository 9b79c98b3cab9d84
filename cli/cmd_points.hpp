#pragma once
// Shared pieces of the `tilekit points` commands (cmd_points*.cpp): where a point set comes
// from (a tile set, recursive Wang tiles, or a reference sampler) and how pictures are written.
#include <CLI/CLI.hpp>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cli/command.hpp"
#include "image/image.hpp"
#include "points/density.hpp"
#include "points/generator.hpp"
#include "points/poisson_tiles.hpp"
#include "points/recursive_tiles.hpp"

namespace tilekit {
class ProgressReporter;
}

namespace tilekit::cli::pts {

// The methods a point set can come from.
inline constexpr const char* kMethods = "corner | wang | dual | recursive | bridson | white | grid | jitter";

struct SourceArgs {
  std::string method = "corner";
  std::string tiles;                                      // a tile-set file (or db:ID); empty: build one in memory
  std::uint32_t colors = 4, edge_colors = 1, points = 0;  // points 0: the method's default
  double rho = 0.75;
  int lloyd = 0, subdivision = 2, levels = 20;
  std::uint64_t tile_seed = 1;
  std::string hash = "long-period", db;
  double base_tile = 0;  // recursive: base tile side (0: chosen from the density)
};
// --method, --tiles, --colors, --edge-colors, --points, --rho, --lloyd, --tile-seed, --subdivision, --levels,
// --hash, --base-tile, --db.
void add_source_options(CLI::App* cmd, SourceArgs& a);

class Source {
 public:
  Source(const SourceArgs& a, int threads, bool progress);
  const std::string& method() const { return a_.method; }
  std::string describe() const;
  bool tiled() const { return tiles_.has_value() || recursive_.has_value(); }
  const points::PoissonTileSet* tiles() const { return tiles_ ? &*tiles_ : nullptr; }
  const points::RecursiveWangTiles* recursive() const { return recursive_ ? &*recursive_ : nullptr; }
  // The tile (or base tile) side at this density; 0 for untiled methods.
  double tile_size(double density) const;
  // The points of `w` at a constant density, or (recursive only) following `density_fn`.
  // `seed` picks the tiling (hash tables) or the sampler's random numbers. `period` > 0: the
  // window is a torus of `period` tiles (tile methods, recursive), or `torus` for the samplers.
  std::vector<double> points(const points::Window& w, double density, std::uint64_t seed, int threads,
                             std::int64_t period = 0, bool torus = false,
                             const points::DensityFunction* density_fn = nullptr,
                             ProgressReporter* progress = nullptr) const;

 private:
  SourceArgs a_;
  std::optional<points::PoissonTileSet> tiles_;
  std::optional<points::RecursiveWangTiles> recursive_;
};

// The subcommands of `tilekit points`, by file.
void add_tiles_command(CLI::App* points, Context& ctx);       // cmd_points.cpp
void add_generate_command(CLI::App* points, Context& ctx);    // cmd_points.cpp
void add_analysis_commands(CLI::App* points, Context& ctx);   // cmd_points_analyze.cpp: analyze, spectrum, zoneplate
void add_recursive_commands(CLI::App* points, Context& ctx);  // cmd_points_recursive.cpp: recursive, objects

// PNG (via atlas/) or SVG by the file name's extension; InputError for others.
void write_image(const std::string& path, const Image& img);
bool is_png(const std::string& path);
bool is_svg(const std::string& path);
// Checks before any work that an --out-style path has one of the accepted extensions.
void check_extension(const std::string& path, const std::vector<std::string>& allowed, const char* flag);

}  // namespace tilekit::cli::pts
