// `tilekit fill --sat` and `--cnf`: the whole map decided by cadical. The blob sheet on the
// smallest torus that can hold 47 tiles (48 cells: 8 x 6) and the refutation of 47 x 1; a CNF
// written by `--cnf`, solved by cadical here and decoded here (variable 1 + cell * T + tile) into
// a cells file that the validator of `fill --cells` accepts.
#include <gtest/gtest.h>

#include <cstdlib>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "tests/cli_runner.hpp"

namespace tilekit::test {
namespace {

bool have_cadical() {
  return std::system("command -v cadical >/dev/null 2>&1") == 0;
}

TEST(FillSat, TheBlobSheetFitsOnA48CellTorusAnd47x1IsRefuted) {
  if (!have_cadical()) GTEST_SKIP() << "cadical is not installed (apt-get install cadical; scripts/setup.sh does)";
  TempDir d;
  CliResult r =
      run_cli("fill --set blob-47 --size 8x6 --torus --cover --sat --seed 1 --map-json " + q(d / "b.json") + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(r.json().at("valid").get<bool>());
  EXPECT_EQ(r.json().at("method"), "sat");
  const nlohmann::json m = nlohmann::json::parse(slurp(d / "b.json"));
  std::set<int> seen;
  int cells = 0;
  for (const auto& row : m.at("cells"))
    for (const auto& c : row) seen.insert(c.get<int>()), ++cells;
  EXPECT_EQ(cells, 48);
  EXPECT_EQ(seen.size(), 47u);
  r = run_cli("fill --set blob-47 --size 47x1 --torus --cover --sat --json");
  EXPECT_EQ(r.code, 1);
  EXPECT_TRUE(r.json().at("region").at("proved").get<bool>());
  r = run_cli("fill --set blob-47 --size 8x6 --torus --cover --sat --checkpoint " + q(d / "c.ckpt"));
  EXPECT_EQ(r.code, 2) << r.err;
}

TEST(FillSat, ACnfSolvedOutsideDecodesToAValidSheet) {
  if (!have_cadical()) GTEST_SKIP() << "cadical is not installed";
  TempDir d;
  // the 16 corner tiles over 2 colours on a 4 x 4 torus: a packing
  CliResult r = run_cli("fill --set complete-corner-2 --size 4x4 --torus --cover --cnf " + q(d / "p.cnf") + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string cnf = slurp(d / "p.cnf");
  EXPECT_NE(cnf.find("p cnf " + std::to_string(r.json().at("variables").get<int>()) + " " +
                     std::to_string(r.json().at("clauses").get<int>())),
            std::string::npos);
  const std::string cmd = "cadical -q " + q(d / "p.cnf") + " > " + q(d / "model.txt");
  ASSERT_EQ(WEXITSTATUS(std::system(cmd.c_str())), 10);  // cadical's exit code for SATISFIABLE
  std::istringstream in(slurp(d / "model.txt"));
  std::vector<int> tile(16, -1);
  for (std::string tok; in >> tok;) {
    if (tok == "v" || tok == "s" || tok == "SATISFIABLE") continue;
    const long v = std::stol(tok);
    if (v > 0 && v <= 16 * 16) {
      ASSERT_EQ(tile[std::size_t((v - 1) / 16)], -1) << "two tiles in one cell";
      tile[std::size_t((v - 1) / 16)] = int((v - 1) % 16);
    }
  }
  std::string cells;
  for (int c = 0; c < 16; ++c) cells += std::to_string(tile[std::size_t(c)]) + (c % 4 == 3 ? "\n" : " ");
  write_text(d / "p.cells", cells);
  r = run_cli("fill --set complete-corner-2 --size 4x4 --torus --cover --cells " + q(d / "p.cells") + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(r.json().at("valid").get<bool>());
  EXPECT_EQ(r.json().at("fixed"), 16);
}

}  // namespace
}  // namespace tilekit::test
