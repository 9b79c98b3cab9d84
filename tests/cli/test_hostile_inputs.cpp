// Hostile and oversized inputs, one class each: nested expressions, requests larger than memory,
// time limits (huge, and in far shards), coordinates far from the origin, tile files whose
// checksum is right but whose contents are not, edited texture manifests, refused outputs that
// must leave existing files alone, and damaged verify checkpoints. Each is exit 0 with a right
// answer or exit 2 with one line naming the problem: never a crash, an internal error or a
// bad_alloc after seconds of work.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "base/hash.hpp"
#include "checkpoints/checkpoint.hpp"
#include "tests/cli_runner.hpp"

using namespace tilekit;
using namespace tilekit::test;
namespace fs = std::filesystem;

namespace {

void expect_refused_saying(const CliResult& r, const std::string& fragment) {
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find(fragment), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("internal error"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

std::string repeated(const std::string& s, int n) {
  std::string out;
  for (int i = 0; i < n; ++i) out += s;
  return out;
}

double seconds_of(const std::function<void()>& f) {
  const auto t0 = std::chrono::steady_clock::now();
  f();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// `text` with `from` replaced by `to` once and its closing "fnv1a64 HEX" line recomputed.
std::string resealed(const std::string& text, const std::string& from, const std::string& to) {
  std::string body = text.substr(0, text.rfind("fnv1a64 "));
  const std::size_t at = body.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  body.replace(at, from.size(), to);
  return body + fmt::format("fnv1a64 {:016x}\n", fnv1a64(body));
}

// The names in a directory (sorted).
std::vector<std::string> files_in(const TempDir& d) {
  std::vector<std::string> out;
  for (const auto& e : fs::directory_iterator(d.path)) out.push_back(e.path().filename().string());
  std::sort(out.begin(), out.end());
  return out;
}

struct MeasuredRun {
  CliResult result;
  long peak_kib = 0;  // the peak resident memory of the largest process the run started
};

// run_cli in a child process of its own, so that getrusage(RUSAGE_CHILDREN) there sees only this
// run's processes (the shell and tilekit) and none of the test binary's earlier ones.
MeasuredRun run_cli_measured(const std::string& prefix, const std::string& args) {
  TempDir io;
  const pid_t child = ::fork();
  if (child == 0) {
    const CliResult r = run_cli_prefixed(prefix, args);
    struct rusage u {};
    ::getrusage(RUSAGE_CHILDREN, &u);
    write_text(io / "code", std::to_string(r.code));
    write_text(io / "out", r.out);
    write_text(io / "err", r.err);
    write_text(io / "peak", std::to_string(u.ru_maxrss));
    ::_exit(0);
  }
  MeasuredRun m;
  int status = 0;
  if (child < 0 || ::waitpid(child, &status, 0) != child || !WIFEXITED(status)) {
    ADD_FAILURE() << "the measuring child failed";
    return m;
  }
  m.result.code = std::stoi(slurp(io / "code"));
  m.result.out = slurp(io / "out");
  m.result.err = slurp(io / "err");
  m.peak_kib = std::stol(slurp(io / "peak"));
  return m;
}

}  // namespace

TEST(HostileInputs, DeeplyNestedDensityExpressionsAreRefusedNotACrash) {
  for (const auto& [open, close] :
       std::vector<std::pair<std::string, std::string>>{{"(", ")"}, {"-", ""}, {"x^", ""}, {"sin(", ")"}}) {
    const std::string e = repeated(open, 800) + "x" + repeated(close, 800);
    expect_refused_saying(
        run_cli("points generate --method recursive --density-expr '" + e + "' --window 0,0,1,1 --density 100 --quiet"),
        "nested deeper than 100 levels");
  }
  expect_refused_saying(run_cli("points generate --method recursive --density-expr '" + repeated("(", 5000) + "x" +
                         repeated(")", 5000) + "' --window 0,0,1,1 --density 100 --quiet"),
                 "more than the 4096 an expression may have");
}

namespace {

// The requests larger than memory, one test each. "Refused before the work" is asserted as sizes,
// not as a wall-clock bound: nothing is written (no output, no temp file) and the process's peak
// memory stays far below what the request needs (kRefusedPeakKib; each request needs gigabytes).
constexpr long kRefusedPeakKib = 512 * 1024;

void expect_refused_small(const TempDir& d, const std::string& args, const std::string& fragment,
                          const std::string& prefix = "") {
  const MeasuredRun m = run_cli_measured(prefix, args);
  expect_refused_saying(m.result, fragment);
  EXPECT_GT(m.peak_kib, 0);  // the measure itself works
  EXPECT_LT(m.peak_kib, kRefusedPeakKib) << "peak resident memory of a refused request";
  EXPECT_EQ(files_in(d), std::vector<std::string>{}) << "a refused request writes nothing";
}

}  // namespace

TEST(HostileInputs, AnImageWindowLargerThanMemoryIsRefused) {
  TempDir d;
  expect_refused_small(d, "points generate --window 0,0,11000,11000 --density 16 --out " + d / "p.png --quiet",
                       "set TILEKIT_MEMORY");
}

TEST(HostileInputs, AStreamedWindowLargerThanTheDiskIsRefused) {
  TempDir d;  // streamed to a point file, the disk bounds the window instead
  expect_refused_small(d, "points generate --window 0,0,1000000,1000000 --density 1000 --out " + d / "p.f64 --quiet",
                       "on disk, more than the");
}

TEST(HostileInputs, ADensityExpressionOfATrillionPointsIsRefused) {
  TempDir d;
  expect_refused_small(d,
                       "points generate --method recursive --density-expr 1e12 --window 0,0,1,1 --density 100 --out " +
                           d / "p.f32 --quiet",
                       "a window of about 1e+12 points");
}

TEST(HostileInputs, TheMemoryLimitIsTheEnvironmentsWhenSet) {
  TempDir d;  // a window that fits the machine is refused under 1 MB
  expect_refused_small(d, "points generate --window 0,0,100,100 --density 10 --out " + d / "p.png --quiet",
                       "more than the limit of 0.000977 GiB (TILEKIT_MEMORY", "env TILEKIT_MEMORY=1M ");
}

TEST(HostileInputs, APointTileRadiusNeedingTooManyPointsIsRefused) {
  TempDir d;
  expect_refused_small(d, "points tiles --rho 1e-6 --no-db --quiet --out " + d / "t.ptiles", "use --rho");
}

TEST(HostileInputs, ATextureSearchBeyondTheRoundLimitIsRefused) {
  TempDir d;
  expect_refused_small(
      d, "texture tiles --exemplar brick --colors 2 --tile-px 16 --search 2000000000 --quiet --out " + d / "tt",
      "candidates a round may try");
}

namespace {

// An image that decodes to 23000 x 23000 grey pixels (529 MB) is refused from its header.
void write_png_bomb(const std::string& path) {
  std::string png("\x89PNG\r\n\x1a\n\0\0\0\x0dIHDR\0\0\x59\xd8\0\0\x59\xd8\x08\0\0\0\0\0\0\0\0", 33);
  png += std::string("\0\0\0\0IEND\xae\x42\x60\x82", 12);
  write_text(path, png);
}

}  // namespace

TEST(HostileInputs, AnExemplarDecodingLargerThanTheImageLimitIsRefusedFromItsHeader) {
  TempDir bomb, d;
  write_png_bomb(bomb / "bomb.png");
  expect_refused_small(
      d, "texture tiles --exemplar " + bomb / "bomb.png --colors 2 --tile-px 16 --quiet --out " + d / "tb",
      "23000x23000 pixels is more than the 268435456 pixels an image may have");
}

TEST(HostileInputs, ADensityImageDecodingLargerThanTheImageLimitIsRefusedFromItsHeader) {
  TempDir bomb, d;
  write_png_bomb(bomb / "bomb.png");
  expect_refused_small(d,
                       "points generate --method recursive --density-image " + bomb / "bomb.png" +
                           " --window 0,0,1,1 --density 100 --quiet --out " + d / "p.f32",
                       "23000x23000 pixels");
}

TEST(HostileInputs, TimeLimitsHoldInFarShardsAndAHugeLimitMeansNone) {
  TempDir d;
  // The split of a far shard used to take longer than the whole count, growing to gigabytes.
  for (const char* shard : {"999999/1000000", "77/100000"}) {
    SCOPED_TRACE(shard);
    CliResult r;
    const double s = seconds_of([&] {
      r = run_cli(std::string("pack --kind corner --colors 3 --mode count --shard ") + shard +
                  " --time-limit 2 --quiet --json --db " + d / "s.sqlite");
    });
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_LT(s, 6);
  }
  const CliResult none = run_cli("aperiodic verify kari-14 --max-k 1 --time-limit 0 --quiet --json");
  const CliResult huge = run_cli("aperiodic verify kari-14 --max-k 1 --time-limit 1e10 --quiet --json");
  ASSERT_EQ(huge.code, 0) << huge.err;
  EXPECT_EQ(huge.json()["verdict"], none.json()["verdict"]);
  EXPECT_EQ(huge.json()["nodes"], none.json()["nodes"]);
  EXPECT_TRUE(huge.json()["stopped_by"].is_null()) << huge.out;
}

TEST(HostileInputs, PointsFarFromTheOriginKeepTheirDistances) {
  TempDir d;
  for (const char* x : {"1000000", "10000000"}) {
    SCOPED_TRACE(x);
    const std::string window = fmt::format("{},{},{},{}", x, x, std::stod(x) + 20, std::stod(x) + 20);
    const CliResult r =
        run_cli("points generate --window " + window + " --density 100 --analyze --quiet --json --out " + d / "p.f64");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_GE(r.json()["radius"]["rho"].get<double>(), 0.75);
    const CliResult a = run_cli("points analyze " + d / "p.f64 --quiet --json");
    ASSERT_EQ(a.code, 0) << a.err;
    EXPECT_GE(a.json()["rho"].get<double>(), 0.75);
    // float32 cannot hold them: refused before the tile set is built, naming the formats that can.
    const auto start = std::chrono::steady_clock::now();
    expect_refused_saying(run_cli("points generate --window " + window + " --density 100 --quiet --out " + d / "p.f32"),
                   "write .f64 or .csv instead");
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 1.0);
    EXPECT_FALSE(fs::exists(d / "p.f32"));
  }
}

// Points are computed in double precision whatever file they go to: a window at 2^53 or 1e15
// (where the rounding reaches the spacing and points coincide) is refused naming the precision
// limit, for .csv and .f64 as for .f32; nearer the origin every point keeps its distance.
TEST(HostileInputs, PointsBeyondDoublePrecisionAreRefusedForEveryFormat) {
  TempDir d;
  for (const char* x : {"9007199254740992", "1000000000000000"})
    for (const char* ext : {"csv", "f64", "png"}) {
      SCOPED_TRACE(std::string(x) + " " + ext);
      const std::string out = d / (std::string("p.") + ext);
      const double x1 = std::stod(x) + 2;  // representable at 2^53 too
      const std::string window = fmt::format("{},{},{:.1f},{:.1f}", x, x, x1, x1);
      expect_refused_saying(run_cli("points generate --window " + window + " --density 100 --quiet --out " + out),
                            "precision limit");
      EXPECT_FALSE(fs::exists(out));
    }
  const CliResult r = run_cli("points generate --window 1000000000000,1000000000000,1000000000001.6,1000000000001.6 "
                              "--density 100 --colors 2 --points 64 --analyze --quiet --json --out " + d / "p.csv");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_GE(r.json()["radius"]["rho"].get<double>(), 0.74);  // the set's own rho, 0.75
}

TEST(HostileInputs, PointTileFilesAreCheckedOnLoad) {
  TempDir d;
  ASSERT_EQ(run_cli("points tiles --colors 1 --points 8 --rho 0.5 --no-db --quiet --out " + d / "t.ptiles").code, 0);
  const std::string text = slurp(d / "t.ptiles");
  const std::size_t tile = text.find("\ntile 0\n") + 8;
  const std::string first = text.substr(tile, text.find('\n', tile) - tile);
  const std::size_t second_at = tile + first.size() + 1;
  const std::string second = text.substr(second_at, text.find('\n', second_at) - second_at);
  write_text(d / "same.ptiles", resealed(text, second + "\n", first + "\n"));
  expect_refused_saying(run_cli("points generate --tiles " + d / "same.ptiles --window 0,0,5,5 --density 10 --quiet"),
                 "the points do not keep rho 0.5: 0 inside tiles");
  write_text(d / "neg.ptiles", resealed(text, "\nradius ", "\nradius -"));
  expect_refused_saying(run_cli("points generate --tiles " + d / "neg.ptiles --window 0,0,5,5 --density 10 --quiet"),
                 "does not belong to rho 0.5");
  write_text(d / "wide.ptiles", resealed(text, "\npoints 8\n", "\npoints 4294967304\n"));
  expect_refused_saying(run_cli("points generate --tiles " + d / "wide.ptiles --window 0,0,5,5 --density 10 --quiet"),
                 "4294967304 is more than 4294967295");
  write_text(d / "ok.ptiles", resealed(text, "tile 0", "tile 0"));
  EXPECT_EQ(run_cli("points generate --tiles " + d / "ok.ptiles --window 0,0,5,5 --density 10 --quiet").code, 0);
}

TEST(HostileInputs, PlaceholdersAndOverflowsDoNotReachTheOutput) {
  // Refused before the default tile set (2 s of building) is made.
  const auto start = std::chrono::steady_clock::now();
  expect_refused_saying(run_cli("points spectrum --sets 1 --set-points 1e7 --quiet --json"), "--set-points 10000000");
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 1.0);
  // From the largest count to four times it the early check lets the command start, and the
  // set's own layout is refused (here a sampler's, of exactly that count).
  expect_refused_saying(run_cli("points spectrum --method white --sets 1 --set-points 400000 --quiet --json"),
                        "use at most about");
  const CliResult o =
      run_cli("points objects --density 10 --window 0,0,3,3 --objects tree:1e308,rock:1e308 --json --quiet");
  ASSERT_EQ(o.code, 0) << o.err;
  const nlohmann::json j = o.json();
  const nlohmann::json& objects = j["objects"];
  EXPECT_GT(objects["tree"]["count"].get<int>(), 0);
  EXPECT_GT(objects["rock"]["count"].get<int>(), 0);
  EXPECT_DOUBLE_EQ(objects["tree"]["expected"].get<double>(), objects["rock"]["expected"].get<double>());
}

namespace {

struct TextureCase {
  TempDir d;
  std::string tiles = d / "tiles";
  TextureCase() {
    const CliResult r =
        run_cli("texture tiles --exemplar brick --colors 2 --tile-px 16 --search 0 --quiet --out " + tiles);
    EXPECT_EQ(r.code, 0) << r.err;
  }
};

}  // namespace

TEST(HostileInputs, TextureManifestsGoThroughTheCheckedReader) {
  TextureCase c;
  const std::string manifest = slurp(c.tiles + "/tiles.json");
  fs::copy(c.tiles, c.d / "t", fs::copy_options::recursive);  // the tiles and their labels/ folder
  const std::string out = c.d / "a.png";
  nlohmann::json wang = nlohmann::json::parse(manifest);
  wang["kind"] = "wang";
  for (const auto& [text, message] : std::vector<std::pair<std::string, std::string>>{
           {"[1]", "expected a JSON object, got [1]"},
           {R"({"kind":"corner","colors":"2"})", "colors: expected an integer"},
           {R"({"kind":"corner","colors":null})", "colors: expected an integer"},
           {R"({"kind":5})", "kind: expected a string, got 5"},
           {wang.dump(), "makes corner tiles, but kind is"}}) {
    SCOPED_TRACE(text);
    write_text(c.d / "t/tiles.json", text);
    expect_refused_saying(run_cli("texture atlas " + c.d / "t --out " + out + " --no-db --quiet"), message);
    EXPECT_FALSE(fs::exists(out));
  }
  // A tile that is a link loop, and a tiles folder that cannot be listed, are the user's to fix.
  write_text(c.d / "t/tiles.json", manifest);
  fs::remove(c.d / "t/tile-0003.png");
  fs::create_symlink("tile-0003.png", c.d / "t/tile-0003.png");
  expect_refused_saying(run_cli("texture atlas " + c.d / "t --out " + out + " --no-db --quiet"),
                 "Too many levels of symbolic links");
}

TEST(HostileInputs, AtlasManifestsAreCheckedInSixtyFourBitsAndAgainstTheirKind) {
  TextureCase c;
  ASSERT_EQ(run_cli("texture atlas " + c.tiles + " --out " + c.d / "atlas.png --no-db --quiet").code, 0);
  const nlohmann::json m = nlohmann::json::parse(slurp(c.d / "atlas.json"));
  const std::vector<std::pair<std::string, std::string>> edits = {
      {R"({"lookup": {"rows": 1000000}})", "lookup.cells: expected an array of 1000000 elements"},
      {R"({"lookup": {"rows": 2147483647}})", "lookup.rows: expected an integer between 1 and"},
      {R"({"lookup": {"cols": -4}})", "lookup.cols: expected an integer between 1 and"},
      {R"({"tile_px": 1073741856})", "tile_px: expected an integer between 1 and 268435456, got 1073741856"},
      {R"({"kind": "wang"})", "kind: \"wang\", but the lookup is a corner packing"}};
  for (const auto& [patch, message] : edits) {
    SCOPED_TRACE(patch);
    nlohmann::json e = m;
    e.merge_patch(nlohmann::json::parse(patch));
    write_text(c.d / "atlas.json", e.dump());
    expect_refused_saying(run_cli("texture render --atlas " + c.d / "atlas.png --size 32x32 --out " + c.d / "r.png --quiet"),
                   message);
    EXPECT_FALSE(fs::exists(c.d / "r.png"));
  }
}

TEST(HostileInputs, ARefusedAtlasLeavesTheExistingOneWhole) {
  TextureCase c;
  ASSERT_EQ(run_cli("texture atlas " + c.tiles + " --out " + c.d / "atlas.png --no-db --quiet").code, 0);
  std::map<std::string, std::string> before;
  for (const auto& e : fs::directory_iterator(c.d.path))
    if (e.is_regular_file()) before[e.path().string()] = slurp(e.path().string());
  // The last file of the set cannot be written (its name is a folder): nothing may change.
  fs::remove(c.d / "atlas.glsl");
  fs::create_directory(c.d / "atlas.glsl");
  before.erase(c.d / "atlas.glsl");
  const CliResult r = run_cli("texture atlas " + c.tiles + " --out " + c.d / "atlas.png --seed 9 --no-db --quiet");
  expect_refused_saying(r, "it is a folder");  // found before any work (cli/io_policy.hpp)
  for (const auto& [path, bytes] : before) EXPECT_EQ(slurp(path), bytes) << path;
  for (const auto& e : fs::directory_iterator(c.d.path))
    EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << e.path();
}

namespace {

// The levels of a verify result without their timings.
nlohmann::json levels(const nlohmann::json& result) {
  nlohmann::json l = result["transducer"]["levels"];
  for (auto& level : l) level.erase("seconds");
  return l;
}

}  // namespace

TEST(HostileInputs, DamagedVerifyCheckpointsAreRefusedOrResumeToTheSameAnswer) {
  TempDir d;
  const std::string ck = d / "d.ckpt";
  ASSERT_EQ(run_cli("aperiodic verify kari-14 --route transducer --max-k 2 --checkpoint " + ck + " --quiet").code, 0);
  const CliResult clean =
      run_cli("aperiodic verify kari-14 --route transducer --max-k 3 --resume " + ck + " --quiet --json");
  ASSERT_EQ(clean.code, 0) << clean.err;
  const std::string text = slurp(ck);
  const std::string body(open_checkpoint(text, "TILEKIT-DECIDE", 1, 1, ck));
  int refused = 0;
  for (std::size_t i = 0; i < body.size(); i += std::max<std::size_t>(1, body.size() / 60)) {
    std::string edited = body;
    edited[i] = char(edited[i] ^ (i % 3 == 0 ? 0x01 : 0x80));
    write_text(d / "e.ckpt", seal_checkpoint("TILEKIT-DECIDE", 1, edited));
    const CliResult r = run_cli("aperiodic verify kari-14 --route transducer --max-k 3 --time-limit 5 --resume " +
                                d / "e.ckpt --quiet --json");
    SCOPED_TRACE(i);
    ASSERT_TRUE(r.code == 0 || r.code == 2) << r.code << " " << r.err;
    if (r.code == 2) {
      ++refused;
      EXPECT_EQ(r.err.find("internal error"), std::string::npos) << r.err;
      continue;
    }
    if (!r.json()["stopped_by"].is_null()) continue;  // an edit that made the run longer: nothing to compare
    // A resumed chain is the one the tiles give: the same verdict and the same levels.
    EXPECT_EQ(r.json()["verdict"], clean.json()["verdict"]);
    EXPECT_EQ(levels(r.json()), levels(clean.json()));
  }
  EXPECT_GT(refused, 0);
}

// Inputs the fuzz harnesses found (fuzz/fuzz_specs.cpp, fuzz_texture_input.cpp): a window
// coordinate beyond double's range, a window of finite coordinates whose area is not (fuzz_driver:
// it was refused later, as "about inf points"), and a 16-bit PNM whose pixels stb would convert
// past its buffer.
TEST(HostileInputs, FuzzFindingsAreRefusedWithExit2) {
  TempDir d;
  expect_refused_saying(run_cli("points generate --window=-1.5e362,0.4,100,200 --density 1 --quiet --out " + d / "p.csv"),
                 "--window must be x0,y0,x1,y1");
  expect_refused_saying(run_cli("points generate --window=-1.5e3,2,4e-121,1e306 --density 1 --quiet --out " + d / "p.csv"),
                 "--window must be x0,y0,x1,y1");
  EXPECT_FALSE(fs::exists(d / "p.csv"));
  write_text(d / "e.ppm", std::string("P6\n1 2\n65535\n") + std::string(3, '\x7b'));
  expect_refused_saying(run_cli("texture tiles --exemplar " + d / "e.ppm" + " --colors 2 --tile-px 16 --quiet --out " +
                         d / "t"),
                 "a 16-bit image that is not a PNG");
  EXPECT_FALSE(fs::exists(d / "t"));
  // A PNM width past int's range was signed overflow inside stb (UBSan), before any check of ours.
  write_text(d / "wide.ppm", std::string("P6\n# a comment\n23000023000\n255\n") + std::string(48, '\0'));
  expect_refused_saying(run_cli("texture tiles --exemplar " + d / "wide.ppm" + " --colors 2 --tile-px 16 --quiet --out " +
                         d / "t"),
                 "a number in its PNM header has 11 digits");
  EXPECT_FALSE(fs::exists(d / "t"));
  // 21 bytes that stb takes for a TGA of 14939 x 2610 pixels, which it filled past the file's end.
  write_text(d / "tiny.tga", std::string("\0\0\x0a" "23000   \x0a[:2\x0a  (\"a", 21));
  expect_refused_saying(run_cli("texture tiles --exemplar " + d / "tiny.tga" + " --colors 2 --tile-px 16 --quiet --out " +
                         d / "t"),
                 "pixels from 21 bytes is damaged");
  EXPECT_FALSE(fs::exists(d / "t"));
}
