#include <gtest/gtest.h>

#include <regex>

#include "tests/cli_runner.hpp"

using namespace tilekit::test;

// `--version` names the version and the commit; every JSON result (through emit, and atlas
// lookup's own JSON text) and every run stored in a results database carry the same text, so a
// result says which build made it.
TEST(Cli, VersionNamesTheCommitAndEveryJsonResultAndStoredRunCarriesIt) {
  CliResult v = run_cli("--version");
  ASSERT_EQ(v.code, 0) << v.err;
  std::smatch m;
  ASSERT_TRUE(
      std::regex_match(v.out, m, std::regex(R"(tilekit (\d+\.\d+\.\d+ \(commit ([0-9a-f]{12}(-dirty)?|unknown)\))\n)")))
      << v.out;
  const std::string line = m[1];
  TempDir d;
  const std::string db = d / "r.sqlite";
  for (const std::string& cmd :
       {std::string("tileset show kari-14 --json"), std::string("atlas lookup --kind corner --colors 3 --no-db"),
        std::string("atlas lookup --kind corner --colors 3 --no-db --format c --json"),
        std::string("tile --set complete-corner-3 --algo direct --size 4x4 --json"),
        "pack --kind corner --colors 2 --method search --quiet --json --db " + db}) {
    CliResult r = run_cli(cmd);
    ASSERT_EQ(r.code, 0) << cmd << ": " << r.err;
    EXPECT_EQ(r.json()["tilekit_version"], line) << cmd;
  }
  CliResult runs = run_cli("db list --table runs --json --db " + db);
  ASSERT_EQ(runs.code, 0) << runs.err;
  ASSERT_EQ(runs.json()["rows"].size(), 1u);
  EXPECT_EQ(runs.json()["rows"][0]["version"], line);
}

TEST(Cli, HelpWorksForEveryCommand) {
  for (const char* cmd : {"", "tileset", "tileset list", "tileset show", "check"}) {
    CliResult r = run_cli(std::string(cmd) + " --help");
    EXPECT_EQ(r.code, 0) << cmd << ": " << r.err;
    EXPECT_NE(r.out.find("Usage"), std::string::npos) << cmd;
  }
}

TEST(Cli, TilesetShowJsonReportsKariAs14Over6) {
  CliResult r = run_cli("tileset show kari-14 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  auto j = r.json();
  EXPECT_EQ(j["tiles"], 14);
  EXPECT_EQ(j["colors"], 6);
  EXPECT_EQ(j["kind"], "wang");
  EXPECT_EQ(j["list"].size(), 14u);
}

TEST(Cli, UnknownTileSetIsExit2WithOneLine) {
  CliResult r = run_cli("tileset show no-such-set");
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err, "tilekit: unknown tile set 'no-such-set': not a built-in name (see `tilekit tileset list`) or a file\n");
}

TEST(Cli, MalformedTileSetFileIsExit2NamingFileAndLine) {
  TempDir d;
  write_text(d / "bad.tiles", "0 1 2 3\n0 1 2\n");
  CliResult r = run_cli("tileset show " + (d / "bad.tiles"));
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err, "tilekit: " + (d / "bad.tiles") + ":2: expected 4 colours (n s w e), found 3 fields\n");
  write_text(d / "dup.tiles", "0 1 2 3\n0 1 2 3\n");
  r = run_cli("tileset show " + (d / "dup.tiles"));
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("duplicate tile"), std::string::npos);
  write_text(d / "range.tiles", "# colors: 3\n0 1 2 3\n");
  r = run_cli("tileset show " + (d / "range.tiles"));
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("out of range"), std::string::npos);
}

TEST(Cli, ImpossibleColourCountsAreExit2) {
  for (const char* name : {"complete-corner-0", "complete-wang-256", "compact-wang-1"}) {
    CliResult r = run_cli(std::string("tileset show ") + name);
    EXPECT_EQ(r.code, 2) << name;
    EXPECT_NE(r.err.find("colours"), std::string::npos) << name << ": " << r.err;
  }
}

TEST(Cli, CheckValidatesAPackingFile) {
  TempDir d;
  // a (4,4;2,2)_2 de Bruijn torus as corner tiles
  int peg[4][4] = {{0, 0, 0, 1}, {0, 0, 1, 0}, {1, 0, 1, 1}, {0, 1, 1, 1}};
  nlohmann::json cells = nlohmann::json::array();
  for (int r = 0; r < 4; ++r) {
    nlohmann::json row = nlohmann::json::array();
    for (int c = 0; c < 4; ++c) {
      int ne = peg[r][(c + 1) % 4], se = peg[(r + 1) % 4][(c + 1) % 4], sw = peg[(r + 1) % 4][c], nw = peg[r][c];
      row.push_back(((ne * 2 + se) * 2 + sw) * 2 + nw);
    }
    cells.push_back(row);
  }
  nlohmann::json j = {{"kind", "corner"}, {"colors", 2}, {"rows", 4}, {"cols", 4}, {"torus", true}, {"cells", cells}};
  write_text(d / "p.json", j.dump());
  CliResult r = run_cli("check " + (d / "p.json") + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.json()["valid"], true);
  EXPECT_EQ(r.json()["packing"], true);
  cells[0][0] = 15;  // the all-ones tile, which does not fit at (0,0)
  j["cells"] = cells;
  write_text(d / "q.json", j.dump());
  r = run_cli("check " + (d / "q.json") + " --json");
  EXPECT_EQ(r.code, 1);
  EXPECT_EQ(r.json()["valid"], false);
  write_text(d / "bad.json", "{\"kind\": \"corner\"");
  r = run_cli("check " + (d / "bad.json"));
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("invalid JSON"), std::string::npos);
}

TEST(Cli, BadFlagIsExit2) {
  CliResult r = run_cli("tileset list --no-such-flag");
  EXPECT_EQ(r.code, 2);
}
