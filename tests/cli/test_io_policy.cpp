// Inputs and outputs as one policy (cli/io_policy.hpp, base/io_paths.hpp): an output that names
// an input (or another output), directly, through a link or a hard link, is exit 2 with one line
// and nothing changed or left behind, for every command with an output; an output whose folder is
// missing is refused before any work (a database is neither changed nor created); and user text
// reaches HTML, SVG, C and GLSL only escaped.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "base/hash.hpp"
#include "tests/build_paths.hpp"
#include "tests/cli_runner.hpp"

using namespace tilekit::test;
namespace fs = std::filesystem;

namespace {

// Every file under `dir` (hidden ones included) and a hash of its bytes: what a refused command
// must leave exactly as it was.
std::map<std::string, std::uint64_t> io_snapshot(const fs::path& dir) {
  std::map<std::string, std::uint64_t> m;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    const std::string rel = fs::relative(e.path(), dir).string();
    if (e.is_symlink() || !e.is_regular_file()) {
      m[rel] = 0;
      continue;
    }
    const std::string bytes = slurp(e.path().string());
    m[rel] = tilekit::StableHash().add(std::string_view(bytes)).fnv();
  }
  return m;
}

// The files every case reads: a results database, a Wang set, a picture, a packing, a point tile
// set and points, a texture tile set with its exemplar and atlas. Made once (about a second).
class IoPolicy : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new TempDir;
    const TempDir& d = *dir_;
    fs::copy_file(std::string(source_dir()) + "/aperiodic/data/finite-14.tiles", d / "S.tiles");
    const std::vector<std::string> make = {
        "pack --kind corner --colors 2 --db " + (d / "R.sqlite") + " --out " + (d / "pk.json") + " --quiet",
        "tile --set complete-corner-4 --algo direct --size 12x12 --tile-size 10 --out " + (d / "I.png"),
        "points tiles --colors 2 --points 16 --no-db --out " + (d / "P.txt") + " --quiet",
        "points generate --tiles " + (d / "P.txt") + " --window 0,0,4,4 --density 10 --out " + (d / "pts.csv") +
            " --quiet",
        "texture tiles --exemplar " + (d / "I.png") + " --colors 2 --tile-px 16 --search 2 --out " + (d / "T") +
            " --quiet",
        "texture atlas " + (d / "T") + " --out " + (d / "A.png") + " --no-db"};
    for (const std::string& m : make) {
      const CliResult r = run_cli(m);
      ASSERT_EQ(r.code, 0) << m << "\n" << r.err;
    }
    fs::create_directory(d / "X");
    fs::copy_file(d / "I.png", d / "X/ex.png");
    fs::create_symlink(d / "R.sqlite", d / "link.sqlite");
    fs::create_hard_link(d / "S.tiles", d / "hard.tiles");
  }
  static void TearDownTestSuite() {
    delete dir_;
    dir_ = nullptr;
  }
  // Runs `args` (with "@" for the fixture folder): exit 2, one line naming the clash, and every
  // file of the fixture as it was.
  static void expect_refused(std::string args, const std::string& words) {
    const TempDir& d = *dir_;
    for (std::size_t p; (p = args.find('@')) != std::string::npos;) args.replace(p, 1, d.path.string());
    const auto before = io_snapshot(d.path);
    const CliResult r = run_cli(args);
    EXPECT_EQ(r.code, 2) << args << "\n" << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << "\n" << r.err;
    EXPECT_NE(r.err.find(words), std::string::npos) << args << "\n" << r.err;
    EXPECT_EQ(io_snapshot(d.path), before) << args;
  }
  static TempDir* dir_;
};
TempDir* IoPolicy::dir_ = nullptr;

TEST_F(IoPolicy, AnOutputOverAnInputIsExitTwoForEveryCommandWithAnOutput) {
  // The issue's four, then every other command that writes a file, a folder or a database.
  const std::vector<std::string> cases = {
      "db export --db @/R.sqlite --out @/R.sqlite",
      "pack --kind corner --colors 2 --db @/R.sqlite --out @/R.sqlite --quiet",
      "aperiodic verify @/S.tiles --checkpoint @/S.tiles --quiet",
      "texture analyze @/I.png --plot @/I.png",
      "tileset show @/S.tiles --out @/S.tiles",
      "check @/pk.json --pegs-out @/pk.json",
      "atlas lookup --colors 2 --db @/R.sqlite --out @/R.sqlite",
      "atlas build --colors 2 --db @/R.sqlite --out @/R.sqlite",
      "tile --set @/S.tiles --algo scanline --size 4x4 --out @/S.tiles",
      "aperiodic convert @/S.tiles --method diagonal --out @/S.tiles",
      "aperiodic convert @/S.tiles --method diagonal --db @/S.tiles",
      "aperiodic smallest --db @/R.sqlite --out @/R.sqlite",
      "aperiodic enumerate --db @/R.sqlite --checkpoint @/R.sqlite --quiet",
      "aperiodic enumerate --db @/R.sqlite --record @/R.sqlite --quiet",
      "points tiles --colors 2 --points 16 --no-db --out @/P.txt --picture @/P.txt",
      "points generate --tiles @/P.txt --window 0,0,4,4 --density 10 --out @/P.txt",
      "points analyze @/pts.csv --plot @/pts.csv",
      "points spectrum --tiles @/P.txt --image @/P.txt",
      "points zoneplate --tiles @/P.txt --out @/P.txt",
      "points objects --tiles @/P.txt --window 0,0,4,4 --density 10 --out @/P.txt",
      "points recursive --points 16 --db @/R.sqlite --out @/R.sqlite",
      "texture atlas @/T --out @/T/tiles.json --no-db",
      "texture atlas @/T --out @/pk.png --db @/pk.json",
      "texture render --atlas @/A.png --out @/A.png",
      "texture render --atlas @/A.png --size 8x8 --out @/A.mip1.png",
      "texture preview --atlas @/A.png --out @/A.json",
      "texture preview --atlas @/A.png --exemplar @/I.png --out @/I.png",
      "tiled tileset --colors 2 --tiles @/T --out @/T",
      "db add @/pk.json --db @/pk.json",
      "db merge @/R.sqlite @/R.sqlite",
      "pack --kind corner --colors 2 --db @/R.sqlite --checkpoint @/R.sqlite --quiet",
  };
  for (const std::string& c : cases) expect_refused(c, "the same file");
  // Through a symbolic link and a hard link.
  expect_refused("db export --db @/link.sqlite --out @/R.sqlite", "the same file");
  expect_refused("aperiodic convert @/hard.tiles --method diagonal --out @/S.tiles", "the same file");
  // Two outputs into one file.
  expect_refused("points analyze @/pts.csv --plot @/new.png --zoneplate @/new.png", "the same file");
  // A folder output that holds an input.
  expect_refused("texture tiles --exemplar @/X/ex.png --colors 2 --out @/X", "holds");
  expect_refused("texture tiles --exemplar @/X/ex.png --colors 2 --out @", "holds");
  // `texture terrain`: the FILE of NAME=FILE[:tileable] is the input.
  expect_refused("texture terrain --terrain a=@/I.png --terrain b=@/X/ex.png:tileable --out @/X", "holds");
  expect_refused("texture terrain --terrain a=@/I.png --terrain b=@/X/ex.png --out @/T --tiled @/X", "holds");
  expect_refused("texture terrain --terrain a=@/I.png --terrain b=@/X/ex.png --out @/T --tiled @/T", "the same file");
}

TEST_F(IoPolicy, ACheckpointMayBeResumedAndWrittenAgainInPlace) {
  const TempDir& d = *dir_;
  TempDir w;
  const CliResult r = run_cli("aperiodic verify " + (d / "S.tiles") + " --checkpoint " + (w / "c.ckpt") + " --resume " +
                              (w / "c.ckpt") + " --quiet");
  EXPECT_EQ(r.err.find("the same file"), std::string::npos) << r.err;
}

// The issue's refusals found only after the work: now found first, the database untouched and
// not created.
TEST_F(IoPolicy, AnUnwritableOutputIsRefusedBeforeAnyWork) {
  const std::string missing = "/nonexistent-tilekit-dir/x.json";
  for (const std::string& c : std::vector<std::string>{
           "pack --kind corner --colors 2 --db @/R.sqlite --out " + missing + " --quiet",
           "pack --kind corner --colors 2 --db @/new.sqlite --out " + missing + " --quiet",
           "aperiodic convert @/S.tiles --method diagonal --db @/R.sqlite --out " + missing,
           "aperiodic convert @/S.tiles --method diagonal --db @/new.sqlite --out " + missing,
           "aperiodic enumerate --max-depth 1 --db @/R.sqlite --record " + missing + " --quiet",
           "aperiodic enumerate --max-depth 1 --db @/new.sqlite --record " + missing + " --quiet",
           "pack --kind corner --colors 2 --db /nonexistent-tilekit-dir/r.sqlite --quiet",
           "db export --db @/R.sqlite --out @/pk.json/x.json",
           "texture tiles --exemplar @/I.png --colors 2 --out @/pk.json/tiles",
           "tile --set complete-corner-2 --algo direct --size 4x4 --out @/T",
       })
    expect_refused(c, "cannot write");
  // A statistics file that cannot be read is refused before the database is created.
  TempDir w;
  write_text(w / "BAD", "junk");
  const CliResult r = run_cli("pack --kind corner --colors 3 --method search --portfolio-stats " + (w / "BAD") +
                              " --db " + (w / "E.sqlite") + " --quiet");
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_FALSE(fs::exists(w / "E.sqlite"));
  EXPECT_FALSE(fs::exists(w / "E.sqlite-journal"));
}

TEST_F(IoPolicy, AReadOnlyFolderIsRefusedBeforeAnyWork) {
  if (::geteuid() == 0) GTEST_SKIP() << "root writes into read-only folders";
  const TempDir& d = *dir_;
  TempDir w;
  fs::create_directory(w / "ro");
  fs::permissions(w / "ro", fs::perms::owner_read | fs::perms::owner_exec);
  const CliResult r = run_cli("db export --db " + (d / "R.sqlite") + " --out " + (w / "ro/x.json"));
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("not writable"), std::string::npos) << r.err;
  fs::permissions(w / "ro", fs::perms::owner_all);
}

// A hostile exemplar file name: the preview page shows it as text, never as markup.
TEST_F(IoPolicy, AHostileFileNameReachesThePreviewPageOnlyAsText) {
  const TempDir& d = *dir_;
  TempDir w;
  // A folder "a<" and a file "script><img ...>": the path reads "a</script><img src=x onerror=...>".
  fs::create_directory(w / "a<");
  const std::string name = w / "a</script><img src=x onerror=alert(1)>.png";
  fs::copy_file(d / "I.png", name);
  const CliResult r =
      run_cli("texture preview --atlas " + (d / "A.png") + " --exemplar " + q(name) + " --out " + (w / "p.html"));
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string html = slurp(w / "p.html");
  EXPECT_EQ(html.find("<img src=x"), std::string::npos);
  EXPECT_NE(html.find("&lt;img src=x onerror=alert(1)&gt;"), std::string::npos);
  // One <script> element of data and one of code, each closed once.
  std::size_t scripts = 0;
  for (std::size_t p = html.find("</script"); p != std::string::npos; p = html.find("</script", p + 1)) ++scripts;
  EXPECT_EQ(scripts, 2u);
}

// A database in a folder with a hostile name (the stored packing's "how" names it): the C headers
// of `atlas lookup` and `texture atlas` compile, and every line of them and of the GLSL that holds
// the name is a comment.
TEST_F(IoPolicy, AHostileNameReachesCHeadersAndShadersOnlyAsCommentText) {
  const TempDir& d = *dir_;
  TempDir w;
  const std::string folder = w / "x */ int evil; /* \\\n#error boom \\";
  fs::create_directories(folder);  // its slashes make folders in folders
  fs::copy_file(d / "R.sqlite", folder + "/r.sqlite");
  const std::string db = q(folder + "/r.sqlite");
  for (const std::string& c :
       std::vector<std::string>{"atlas lookup --colors 2 --format c --db " + db + " --out " + (w / "l.h"),
                                "atlas lookup --colors 2 --format glsl --db " + db + " --out " + (w / "l.glsl"),
                                "texture atlas " + (d / "T") + " --db " + db + " --out " + (w / "a.png")}) {
    const CliResult r = run_cli(c);
    ASSERT_EQ(r.code, 0) << c << "\n" << r.err;
  }
  for (const char* h : {"l.h", "a.h"}) {
    const std::string cc = "cc -fsyntax-only -x c " + q(w / h) + " >" + (w / "cc.txt") + " 2>&1";
    EXPECT_EQ(std::system(cc.c_str()), 0) << h << "\n" << slurp(w / "cc.txt");
  }
  for (const char* f : {"l.h", "l.glsl", "a.h", "a.glsl"}) {
    const std::string text = slurp(w / f);
    EXPECT_NE(text.find("evil"), std::string::npos) << f;  // the name is there, as comment text
    std::size_t p = 0;
    for (std::size_t e; (e = text.find('\n', p)) != std::string::npos; p = e + 1) {
      const std::string l = text.substr(p, e - p);
      if (l.find("evil") == std::string::npos && l.find("boom") == std::string::npos) continue;
      EXPECT_TRUE(l.rfind("//", 0) == 0 || l.rfind(" * ", 0) == 0 || l.rfind("/* ", 0) == 0) << f << ": " << l;
      // No comment ends before the line does.
      EXPECT_EQ(l.find("*/"), l.size() >= 2 && l.substr(l.size() - 2) == "*/" ? l.size() - 2 : std::string::npos)
          << f << ": " << l;
    }
  }
}

// A hostile points file name in an SVG plot's legend: text, not markup.
TEST_F(IoPolicy, AHostileNameReachesAnSvgPlotOnlyAsText) {
  const TempDir& d = *dir_;
  TempDir w;
  const std::string name = "<svg onload=alert(1)>.csv";
  fs::copy_file(d / "pts.csv", w / name);
  const CliResult r = run_cli("points analyze " + q(w / name) + " --window 0,0,4,4 --plot " + (w / "p.svg"));
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string svg = slurp(w / "p.svg");
  EXPECT_EQ(svg.find("<svg onload"), std::string::npos);
}

// Slurm scripts: a carriage return in a run folder or a directive is refused (the other hostile
// names are quoted: tests/cluster).
TEST_F(IoPolicy, AControlCharacterInASlurmDirectiveIsRefused) {
  TempDir w;
  const CliResult r = run_cli("cluster submit --kind corner --colors 4 --shards 2 --time 1:00:00 --dry-run --run-dir " +
                              q(w / "run\rx"));
  EXPECT_EQ(r.code, 2) << r.out;
  const CliResult s = run_cli("cluster submit --kind corner --colors 4 --shards 2 --time 1:00:00 --dry-run --run-dir " +
                              (w / "run") + " --sbatch-arg " + q("--account=a\rb"));
  EXPECT_EQ(s.code, 2) << s.out;
}

}  // namespace
