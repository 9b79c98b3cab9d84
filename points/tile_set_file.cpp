#include "points/tile_set_file.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

#include "base/atomic_file.hpp"
#include "base/error.hpp"
#include "base/hash.hpp"
#include "checkpoints/results_db.hpp"

namespace tilekit::points {

namespace {

constexpr const char* kMagic = "TILEKIT-POINT-TILES 1";

// Lines of a text with their numbers, for error messages.
class Lines {
 public:
  Lines(const std::string& text, std::string source) : text_(text), source_(std::move(source)) {}
  bool next(std::string_view& line) {
    if (pos_ >= text_.size()) return false;
    const std::size_t end = text_.find('\n', pos_);
    line = std::string_view(text_).substr(pos_, (end == std::string::npos ? text_.size() : end) - pos_);
    pos_ = end == std::string::npos ? text_.size() : end + 1;
    ++number_;
    return true;
  }
  std::string_view expect(const char* what) {
    std::string_view line;
    if (!next(line)) fail(fmt::format("ends before {}", what));
    return line;
  }
  [[noreturn]] void fail(const std::string& what) const {
    throw InputError(fmt::format("{}:{}: {}", source_, number_, what));
  }
  std::size_t offset() const { return pos_; }

 private:
  const std::string& text_;
  std::string source_;
  std::size_t pos_ = 0;
  int number_ = 0;
};

double parse_double(Lines& in, std::string_view s) {
  double v = 0;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
  if (r.ec != std::errc() || r.ptr != s.data() + s.size() || !std::isfinite(v))
    in.fail(fmt::format("'{}' is not a number", s));
  return v;
}

std::uint64_t parse_uint(Lines& in, std::string_view s) {
  std::uint64_t v = 0;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
  if (r.ec != std::errc() || r.ptr != s.data() + s.size()) in.fail(fmt::format("'{}' is not a count", s));
  return v;
}

// "key value" -> value, failing unless the key is `key`.
std::string_view keyed(Lines& in, const char* key) {
  const std::string_view line = in.expect(key);
  const std::string_view k(key);
  if (line.size() <= k.size() + 1 || line.substr(0, k.size()) != k || line[k.size()] != ' ')
    in.fail(fmt::format("expected '{} ...', got '{}'", key, line));
  return line.substr(k.size() + 1);
}

}  // namespace

std::string poisson_tiles_to_text(const PoissonTileSet& set) {
  std::string out;
  out.reserve(set.tiles.size() * set.points * 40 + 256);
  out += fmt::format("{}\nmethod {}\ncolors {}\npoints {}\nrho {}\nradius {:.17g}\nlloyd {}\nseed {}\ntiles {}\n",
                     kMagic, method_name(set.method), set.colours, set.points, set.rho, set.radius, set.lloyd, set.seed,
                     set.tiles.size());
  for (std::size_t t = 0; t < set.tiles.size(); ++t) {
    out += fmt::format("tile {}\n", t);
    for (const Point2& p : set.tiles[t]) out += fmt::format("{:.17g} {:.17g}\n", p.x, p.y);
  }
  out += "end\n";
  out += fmt::format("fnv1a64 {:016x}\n", fnv1a64(out));
  return out;
}

PoissonTileSet poisson_tiles_from_text(const std::string& text, const std::string& source) {
  Lines in(text, source);
  if (in.expect("the header") != kMagic) in.fail(fmt::format("not a point tile-set file (expected '{}')", kMagic));
  PoissonTileSet set;
  set.method = parse_poisson_tile_method(std::string(keyed(in, "method")));
  set.colours = std::uint32_t(parse_uint(in, keyed(in, "colors")));
  set.points = std::uint32_t(parse_uint(in, keyed(in, "points")));
  set.rho = parse_double(in, keyed(in, "rho"));
  set.radius = parse_double(in, keyed(in, "radius"));
  set.lloyd = int(parse_uint(in, keyed(in, "lloyd")));
  set.seed = parse_uint(in, keyed(in, "seed"));
  const std::uint64_t tiles = parse_uint(in, keyed(in, "tiles"));
  PoissonTileParams p;
  p.method = set.method, p.colours = set.colours, p.points = set.points, p.rho = set.rho, p.lloyd = set.lloyd;
  try {
    check_poisson_tile_params(p);
  } catch (const InputError& e) {
    in.fail(e.what());
  }
  const std::uint64_t l = set.lattice_colours();
  const std::uint64_t expected =
      set.method == PoissonTileMethod::Wang ? std::uint64_t(std::pow(double(set.colours), 12)) : l * l * l * l;
  if (tiles != expected)
    in.fail(fmt::format("{} tiles, but a {} set over {} colours has {}", tiles, method_name(set.method), set.colours,
                        expected));
  set.tiles.resize(tiles);
  for (std::uint64_t t = 0; t < tiles; ++t) {
    if (parse_uint(in, keyed(in, "tile")) != t) in.fail(fmt::format("expected tile {}", t));
    set.tiles[t].resize(set.points);
    for (Point2& q : set.tiles[t]) {
      const std::string_view line = in.expect("a point");
      const std::size_t sp = line.find(' ');
      if (sp == std::string_view::npos) in.fail(fmt::format("expected 'u v', got '{}'", line));
      q = {parse_double(in, line.substr(0, sp)), parse_double(in, line.substr(sp + 1))};
      if (!(q.x >= 0 && q.x < 1 && q.y >= 0 && q.y < 1)) in.fail("tile coordinates must lie in [0, 1)");
    }
  }
  if (in.expect("end") != "end") in.fail("expected 'end'");
  const std::size_t body = in.offset();
  const std::string_view sum = keyed(in, "fnv1a64");
  if (sum != fmt::format("{:016x}", fnv1a64(std::string_view(text).substr(0, body))))
    in.fail("checksum mismatch: the file is damaged or was edited");
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
  std::ifstream f(path, std::ios::binary);
  if (!f) throw InputError(fmt::format("{}: cannot open", path));
  std::stringstream b;
  b << f.rdbuf();
  return poisson_tiles_from_text(b.str(), path);
}

std::string poisson_tiles_name(const PoissonTileSet& set) {
  return fmt::format("poisson-{}-C{}-N{}-rho{}-seed{}", method_name(set.method), set.colours, set.points, set.rho,
                     set.seed);
}

std::int64_t store_poisson_tiles(ResultsDb& db, const PoissonTileSet& set, const std::string& text, int threads) {
  RunRecord run;
  run.command = "points tiles";
  run.params = {{"method", method_name(set.method)},
                {"colors", set.colours},
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
