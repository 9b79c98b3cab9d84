// `tilekit fill` end to end: --help and one JSON object, a refused request (exit 1) naming its
// window, bad input (exit 2) writing nothing, fills of a Tilekit set and of a WFC set read by the
// real Tiled (headless export, tmxrasterizer equal to Tilekit's picture), and (slow) a 4096 x 4096
// fill stopped by SIGTERM and resumed ending with the map of an uninterrupted run.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>

#include <chrono>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "image/image.hpp"
#include "tests/tilemap/tiled_checker.hpp"

namespace tilekit::test {
namespace {

std::string wfc(const std::string& name) {
  return (std::filesystem::path(TILEKIT_SOURCE_DIR) / "tilemap" / "data" / "wfc" / (name + ".xml")).string();
}

TEST(FillCli, HelpAndOneJsonObject) {
  const CliResult h = run_cli("fill --help");
  EXPECT_EQ(h.code, 0);
  for (const char* flag : {"--set", "--size", "--torus", "--cells", "--weight", "--threads", "--seed", "--time-limit",
                           "--checkpoint", "--resume", "--png", "--tiled", "--json", "--order", "--sat", "--cnf"})
    EXPECT_NE(h.out.find(flag), std::string::npos) << flag;
  const CliResult r = run_cli("fill --set complete-corner-3 --size 20x11 --torus --seed 4 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json j = r.json();
  EXPECT_TRUE(j.at("found").get<bool>());
  EXPECT_TRUE(j.at("valid").get<bool>());
  EXPECT_EQ(j.at("tiles"), 81);
  std::uint64_t cells = 0;
  for (const auto& f : j.at("frequencies")) cells += f.at("cells").get<std::uint64_t>();
  EXPECT_EQ(cells, 220u);
  // the same seed, the same map
  EXPECT_EQ(run_cli("fill --set complete-corner-3 --size 20x11 --torus --seed 4 --json").json().at("map_hash"),
            j.at("map_hash"));
}

TEST(FillCli, AnIncompleteSetAndFixedCellsFromACellsFile) {
  TempDir d;
  // compact-wang-3 is not complete; pin three of its tiles
  write_text(d / "c.cells", "# pinned\n0 . . . . .\n. . . . . .\n. . . 5 . .\n. . . . . 9\n");
  const CliResult r =
      run_cli("fill --set compact-wang-3 --size 6x4 --cells " + q(d / "c.cells") + " --map-json " + q(d / "m.json") + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json m = nlohmann::json::parse(slurp(d / "m.json"));
  EXPECT_EQ(m.at("cells").at(0).at(0), 0);
  EXPECT_EQ(m.at("cells").at(2).at(3), 5);
  EXPECT_EQ(m.at("cells").at(3).at(5), 9);
  EXPECT_EQ(r.json().at("fixed"), 3);
}

TEST(FillCli, AnImpossibleRequestExits1NamingTheWindow) {
  TempDir d;
  // in Knots, a cross may not sit left of an empty tile
  write_text(d / "bad.cells", ". . . . . .\n. . . . . .\n. . cross empty . .\n. . . . . .\n");
  CliResult r = run_cli("fill --set " + q(wfc("Knots")) + " --size 6x4 --cells " + q(d / "bad.cells") + " --png " +
                        q(d / "out.png"));
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_NE(r.err.find("no fill exists: the 2x1 cells at column 2, row 2 cannot be completed"), std::string::npos)
      << r.err;
  EXPECT_FALSE(std::filesystem::exists(d / "out.png"));
  r = run_cli("fill --set " + q(wfc("Knots")) + " --size 6x4 --cells " + q(d / "bad.cells") + " --json");
  EXPECT_EQ(r.code, 1);
  const nlohmann::json j = r.json();
  EXPECT_FALSE(j.at("found").get<bool>());
  EXPECT_TRUE(j.at("region").at("proved").get<bool>());
  EXPECT_EQ(j.at("region").at("cols"), 2);
}

TEST(FillCli, BadInputExits2AndWritesNothing) {
  TempDir d;
  write_text(d / "short.cells", ". .\n");
  write_text(d / "name.cells", "nosuchtile .\n. .\n");
  for (const std::string& args : std::vector<std::string>{"--set " + q(wfc("Knots")) + " --subset NoSuch --size 8x8", "--set " + q(wfc("Knots")) + " --size 2x2 --cells " + q(d / "short.cells"),
        "--set " + q(wfc("Knots")) + " --size 2x2 --cells " + q(d / "name.cells"), "--set complete-corner-2 --size 0x3",
        "--set complete-corner-2 --size 4x4 --subset Dense", "--set complete-corner-2 --size 4x4 --weight 3=-1",
        "--set no-such-set --size 4x4", "--set complete-corner-2 --size 4x4 --time-limit nan", "--set complete-corner-2 --size 4x4 --order random"}) {
    const CliResult r = run_cli("fill " + args + " --png " + q(d / "o.png"));
    EXPECT_EQ(r.code, 2) << args << "\n" << r.err;
    EXPECT_FALSE(std::filesystem::exists(d / "o.png")) << args;
  }
}

// The blob sheet: all 47 tiles of the 8-neighbour blob set on an 8 x 8 torus, checked by the
// validator (edge triples) and counted here; a 1-cell-high torus cannot hold them (proved at once).
TEST(FillCli, TheBlobSheetHoldsAll47TilesOnTheTorus) {
  TempDir d;
  CliResult r = run_cli("fill --set blob-47 --size 8x8 --torus --cover --seed 1 --map-json " + q(d / "b.json") + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(r.json().at("valid").get<bool>());
  EXPECT_EQ(r.json().at("tiles"), 47);
  const nlohmann::json m = nlohmann::json::parse(slurp(d / "b.json"));
  std::set<int> seen;
  for (const auto& row : m.at("cells"))
    for (const auto& c : row) seen.insert(c.get<int>());
  EXPECT_EQ(seen.size(), 47u);
  r = run_cli("fill --set blob-47 --size 47x1 --torus --cover --json");
  EXPECT_EQ(r.code, 1);
  EXPECT_TRUE(r.json().at("region").at("proved").get<bool>());
}

// Tiled reads a fill of a Tilekit set and of a WFC set; every neighbour pair agrees on its
// wangid in Tiled's export; tmxrasterizer draws Tilekit's own picture of the WFC fill.
TEST(FillReal, TiledReadsTheFillsAndDrawsTheirPictures) {
  if (!tiled::installed()) GTEST_SKIP() << tiled::kSkip;
  TempDir d;
  CliResult r = run_cli("fill --set complete-corner-3 --size 19x13 --seed 2 --tile-px 8 --tiled " + q(d / "c") + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string tmx = r.json().at("tmx");
  ASSERT_EQ(tiled::run_qt("tiled", "--embed-tilesets --export-map json " + q(tmx) + " " + q(d / "c.json")), 0);
  const nlohmann::json j = nlohmann::json::parse(slurp(d / "c.json"));
  const auto& ts = j.at("tilesets").at(0);
  const tiled::WangSetJson w = tiled::wang_set_of(ts);
  std::vector<int> ids;
  for (const auto& g : j.at("layers").at(0).at("data")) ids.push_back(g.get<int>() - ts.at("firstgid").get<int>());
  ASSERT_EQ(ids.size(), 19u * 13u);
  const auto bad = tiled::mismatches(w, ids, 13, 19, false);
  EXPECT_TRUE(bad.empty()) << bad.front();

  r = run_cli("fill --set " + q(wfc("Circuit")) + " --subset Turnless --size 20x12 --torus --seed 3 --png " +
              q(d / "w.png") + " --tiled " + q(d / "w") + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string wtmx = r.json().at("tmx");
  ASSERT_EQ(tiled::run_qt("tiled", "--export-map json " + q(wtmx) + " " + q(d / "w.json")), 0);
  ASSERT_EQ(tiled::run_qt("tmxrasterizer", q(wtmx) + " " + q(d / "tiled.png")), 0);
  EXPECT_EQ(tiled::differing_pixels(read_image(d / "tiled.png"), read_image(d / "w.png")), 0);
}

// A 4096 x 4096 fill stopped by SIGTERM (exit 3, checkpoint) and resumed ends with the map of an
// uninterrupted run with the same seed (one thread: the map is a function of the request).
TEST(FillKill, A4096FillStoppedAndResumedEqualsTheWholeRun) {
  TempDir d;
  const std::string base = "fill --set " + q(wfc("Knots")) + " --subset Standard --size 4096x4096 --torus --seed 11 --json --quiet";
  const CliResult whole = run_cli(base);
  ASSERT_EQ(whole.code, 0) << whole.err;
  const std::string ck = d / "f.ckpt";
  std::vector<std::string> args{"fill", "--set", wfc("Knots"), "--subset", "Standard", "--size", "4096x4096", "--torus",
                                "--seed", "11", "--checkpoint", ck, "--checkpoint-every", "0.2", "--json", "--quiet"};
  const pid_t pid = spawn_tilekit(args, d / "out", d / "err");
  ASSERT_GT(pid, 0);
  ASSERT_TRUE(wait_until_catching(pid, SIGTERM, 30));
  // Stopped as soon as a checkpoint written during the work replaces the one written before it
  // (every 0.2 s; each is renamed into place, a new inode), however fast or loaded the machine.
  const auto inode = [&] {
    struct stat st {};
    return ::stat(ck.c_str(), &st) == 0 ? st.st_ino : ino_t(0);
  };
  ino_t first = 0;
  for (int i = 0; i < 600 && (first = inode()) == 0; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(50));
  ASSERT_NE(first, ino_t(0)) << "no checkpoint after 30 s";
  for (int i = 0; i < 600 && inode() == first; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  kill(pid, SIGTERM);
  ASSERT_EQ(wait_exit(pid), 3) << slurp(d / "err");
  EXPECT_NE(slurp(d / "err").find("checkpoint written to"), std::string::npos);
  args.push_back("--resume");
  args.push_back(ck);
  std::string cmd = "fill";
  for (std::size_t i = 1; i < args.size(); ++i) cmd += " " + q(args[i]);
  const CliResult resumed = run_cli(cmd);
  ASSERT_EQ(resumed.code, 0) << resumed.err;
  EXPECT_TRUE(resumed.json().at("resumed").get<bool>());
  EXPECT_GT(resumed.json().at("blocks").get<int>(), 0);
  EXPECT_LT(resumed.json().at("blocks").get<int>(), 64 * 64) << "the resumed run did not start where the first stopped";
  EXPECT_EQ(resumed.json().at("map_hash"), whole.json().at("map_hash"));
}

}  // namespace
}  // namespace tilekit::test
