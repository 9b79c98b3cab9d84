#include "points/tile_set_file.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <limits>

#include "base/atomic_file.hpp"
#include "base/error.hpp"
#include "base/hash.hpp"
#include "base/input.hpp"
#include "base/parallel.hpp"
#include "points/text_format.hpp"
#include "results/results_db.hpp"

namespace tilekit::points {

namespace {

constexpr std::string_view kMagic = "TILEKIT-POINT-TILES ";
// Version 1: corner, dual and edge-based sets; 2 adds the line "edge_colors E" after "colors".
constexpr std::uint64_t kVersion = 2;

}  // namespace

std::string poisson_tiles_to_text(const PoissonTileSet& set) {
  std::string out;
  out.reserve(set.tiles.size() * set.points * 40 + 256);
  // The oldest version that holds the set, so that older tilekits read what they can.
  if (set.edge_colours > 1)
    out += fmt::format("{}2\nmethod {}\ncolors {}\nedge_colors {}\n", kMagic, method_name(set.method), set.colours,
                       set.edge_colours);
  else
    out += fmt::format("{}1\nmethod {}\ncolors {}\n", kMagic, method_name(set.method), set.colours);
  out += fmt::format("points {}\nrho {}\nradius {:.17g}\nlloyd {}\nseed {}\ntiles {}\n", set.points, set.rho,
                     set.radius, set.lloyd, set.seed, set.tiles.size());
  for (std::size_t t = 0; t < set.tiles.size(); ++t) {
    out += fmt::format("tile {}\n", t);
    for (const Point2& p : set.tiles[t]) out += fmt::format("{:.17g} {:.17g}\n", p.x, p.y);
  }
  out += "end\n";
  return text::with_checksum(std::move(out));
}

PoissonTileSet poisson_tiles_from_text(const std::string& text, const std::string& source) {
  text::LineReader in(text, source);
  const std::string_view head = in.expect("the header");
  if (!head.starts_with(kMagic)) in.fail(fmt::format("not a point tile-set file (expected '{}{}')", kMagic, kVersion));
  const std::uint64_t version = in.count(head.substr(kMagic.size()));
  if (version > kVersion)
    in.fail(fmt::format("point tile-set format version {} is newer than this tilekit reads (versions 1 to {})", version,
                        kVersion));
  if (version == 0) in.fail("point tile-set format version 0 does not exist");
  PoissonTileSet set;
  set.method = parse_poisson_tile_method(std::string(in.keyed("method")));
  set.colours = std::uint32_t(in.count(in.keyed("colors"), std::numeric_limits<std::uint32_t>::max()));
  if (version >= 2)
    set.edge_colours = std::uint32_t(in.count(in.keyed("edge_colors"), std::numeric_limits<std::uint32_t>::max()));
  set.points = std::uint32_t(in.count(in.keyed("points"), std::numeric_limits<std::uint32_t>::max()));
  set.rho = in.number(in.keyed("rho"));
  set.radius = in.number(in.keyed("radius"));
  set.lloyd = int(in.count(in.keyed("lloyd"), std::numeric_limits<int>::max()));
  set.seed = in.count(in.keyed("seed"));
  const std::uint64_t tiles = in.count(in.keyed("tiles"));
  PoissonTileParams p;
  p.method = set.method, p.colours = set.colours, p.points = set.points, p.rho = set.rho, p.lloyd = set.lloyd;
  p.edge_colours = set.edge_colours;
  try {
    check_poisson_tile_params(p);
  } catch (const InputError& e) {
    in.fail(e.what());
  }
  const std::uint64_t l = set.lattice_colours(), ec = set.edge_colours;
  const std::uint64_t expected = set.method == PoissonTileMethod::Wang
                                     ? std::uint64_t(std::pow(double(set.colours), 12))
                                     : l * l * l * l * ec * ec * ec * ec;
  if (tiles != expected)
    in.fail(fmt::format("{} tiles, but a {} set over {} colours and {} edge colours has {}", tiles,
                        method_name(set.method), set.colours, set.edge_colours, expected));
  set.tiles.resize(tiles);
  for (std::uint64_t t = 0; t < tiles; ++t) {
    if (in.count(in.keyed("tile")) != t) in.fail(fmt::format("expected tile {}", t));
    set.tiles[t].resize(set.points);
    for (Point2& q : set.tiles[t]) {
      const std::string_view line = in.expect("a point");
      const std::size_t sp = line.find(' ');
      if (sp == std::string_view::npos) in.fail(fmt::format("expected 'u v', got '{}'", line));
      q = {in.number(line.substr(0, sp)), in.number(line.substr(sp + 1))};
      if (!(q.x >= 0 && q.x < 1 && q.y >= 0 && q.y < 1)) in.fail("tile coordinates must lie in [0, 1)");
    }
  }
  if (in.expect("end") != "end") in.fail("expected 'end'");
  in.checksum();
  // A checksum proves only that the file is as written: the radius and the distances it
  // promises are checked as for a newly built set (the independent neighbour check).
  const double radius = set.rho * max_poisson_radius(set.points);
  if (!(std::abs(set.radius - radius) <= 1e-9 * radius))
    throw InputError(fmt::format("{}: radius {} does not belong to rho {} with {} points (it is {})", source,
                                 set.radius, set.rho, set.points, radius));
  const TileSetCheck c = check_poisson_tiles(set, resolve_threads(0));
  if (c.points_off_count || !(c.rho_within >= set.rho) || !(c.rho_across >= set.rho))
    throw InputError(fmt::format(
        "{}: the points do not keep rho {}: {:.4g} inside tiles, {:.4g} across tile borders ({} tiles without {} points)",
        source, set.rho, c.rho_within, c.rho_across, c.points_off_count, set.points));
  return set;
}

void write_poisson_tiles(const std::string& path, const PoissonTileSet& set) {
  write_file_atomic(path, poisson_tiles_to_text(set));
}

PoissonTileSet read_poisson_tiles(const std::string& path, const std::string& db_path) {
  if (path.starts_with("db:")) {
    std::int64_t id = 0;
    const std::string num = path.substr(3);
    const auto r = std::from_chars(num.data(), num.data() + num.size(), id);
    if (r.ec != std::errc() || r.ptr != num.data() + num.size() || id <= 0)
      throw InputError(fmt::format("'{}': expected db:ID with a positive tile-set id", path));
    DbOpenOptions o;
    o.create = false;
    o.read_only = true;
    ResultsDb db(db_path.empty() ? ResultsDb::default_path() : db_path, o);
    const auto row = db.tileset(id);
    if (!row) throw NotFound(fmt::format("{}: no tile set with id {}", db.path(), id));
    return poisson_tiles_from_text(row->text, fmt::format("{} tile set {}", db.path(), id));
  }
  return poisson_tiles_from_text(read_input_file(path, "point tile-set file"), path);
}

std::string poisson_tiles_name(const PoissonTileSet& set) {
  const std::string edges = set.edge_colours > 1 ? fmt::format("-E{}", set.edge_colours) : "";
  return fmt::format("poisson-{}-C{}{}-N{}-rho{}-seed{}", method_name(set.method), set.colours, edges, set.points,
                     set.rho, set.seed);
}

std::int64_t store_poisson_tiles(ResultsDb& db, const PoissonTileSet& set, const std::string& text, int threads) {
  RunRecord run;
  run.command = "points tiles";
  run.params = {{"method", method_name(set.method)},
                {"colors", set.colours},
                {"edge_colors", set.edge_colours},
                {"points", set.points},
                {"rho", set.rho},
                {"lloyd", set.lloyd},
                {"seed", set.seed}};
  run.status = "complete";
  run.solutions = 1;
  run.seconds = set.seconds;
  run.threads = threads;
  run.id = db.begin_run(run);
  db.finish_run(run);
  return db.add_tileset(poisson_tiles_name(set),
                        set.method == PoissonTileMethod::Wang ? TileKind::Wang : TileKind::Corner, set.tiles.size(),
                        set.lattice_colours(), fmt::format("{:016x}", stable_hash64(text)),
                        fmt::format("tilekit points tiles (run {})", run.id), text);
}

}  // namespace tilekit::points
