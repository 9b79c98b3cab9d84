#include <gtest/gtest.h>

#include <random>
#include <regex>

#include "atlas/lookup.hpp"
#include "base/error.hpp"
#include "cli/packing_lookup.hpp"
#include "results/results_db.hpp"
#include "tests/cli_runner.hpp"
#include "tilesets/constructions.hpp"
#include "tilesets/validator.hpp"

using namespace tilekit;
using namespace tilekit::test;

namespace {

AtlasLookup no_db(TileKind k, std::uint32_t c) {
  return atlas_lookup(k, c);
}

void expect_lookup_consistent(const AtlasLookup& a) {
  ASSERT_EQ(a.cells.size(), std::size_t(a.rows) * std::size_t(a.cols));
  ASSERT_EQ(a.positions.size(), a.cells.size());
  for (std::size_t i = 0; i < a.cells.size(); ++i) {
    const auto [r, c] = a.positions[a.cells[i]];
    ASSERT_EQ(std::size_t(r) * std::size_t(a.cols) + std::size_t(c), i) << "tile " << a.cells[i];
  }
  if (a.closed_form) {
    for (TileIndex t = 0; t < a.positions.size(); ++t)
      ASSERT_EQ(packing_position(a.kind, a.colours, t), a.positions[t]);
  }
}

// Runs a shell command, returns its exit status.
int sh(const std::string& cmd) {
  int status = std::system(cmd.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128;
}

}  // namespace

TEST(AtlasLookup, LookupAndInverseAgreeForEveryTile) {
  for (std::uint32_t c : {1u, 2u, 3u, 4u, 5u, 6u, 7u, 10u, 11u, 12u})
    expect_lookup_consistent(no_db(TileKind::Corner, c));
  for (std::uint32_t c : {2u, 3u, 4u, 6u}) expect_lookup_consistent(no_db(TileKind::Wang, c));
}

TEST(AtlasLookup, ConstructionsAreUsedWithoutADatabase) {
  AtlasLookup a = no_db(TileKind::Corner, 5);
  EXPECT_EQ(a.source, "construct");
  EXPECT_EQ(a.how, "debruijn-triangular");
  EXPECT_TRUE(a.closed_form);
  EXPECT_EQ(a.rows, 25);
}

TEST(AtlasLookup, AStoredPackingInTheDatabaseComesFirst) {
  TempDir d;
  // A different C=3 packing than the construction: the constructed one shifted by (1, 2).
  Tiling t = construct_packing(TileKind::Corner, 3)->tiling, shifted = t;
  for (int r = 0; r < 9; ++r)
    for (int c = 0; c < 9; ++c) shifted.at(r, c) = t.at((r + 1) % 9, (c + 2) % 9);
  {
    ResultsDb db(d / "r.sqlite");
    SolutionRecord s;
    s.tiling = shifted;
    s.method = "search";
    s.validated = true;
    db.add_solution(s);
  }
  // The database through packing/ (find_lookup_packing), laid out by atlas/: what `atlas lookup` does.
  AtlasLookup a = cli::lookup_with_database(TileKind::Corner, 3, d / "r.sqlite");
  EXPECT_EQ(a.source, "db");
  EXPECT_FALSE(a.closed_form);
  EXPECT_EQ(a.cells, shifted.cells);
  expect_lookup_consistent(a);
  // A database that does not exist is not created by a lookup.
  EXPECT_EQ(cli::lookup_with_database(TileKind::Corner, 3, d / "none.sqlite").source, "construct");
  EXPECT_FALSE(std::filesystem::exists(d / "none.sqlite"));
  // atlas/'s own lookup reads no database: the construction, whatever a database holds.
  EXPECT_EQ(atlas_lookup(TileKind::Corner, 3).cells, t.cells);
}

TEST(AtlasLookup, EveryCornerColourCountFromTwoToThirtyTwoAnswersAValidatedPacking) {
  // The odd closed form, coprime products, the stored packings and the binary lift.
  for (std::uint32_t c = 2; c <= 32; ++c) {
    AtlasLookup a = no_db(TileKind::Corner, c);
    EXPECT_EQ(a.source, "construct") << c;
    ASSERT_EQ(a.rows, int(c * c)) << c;
    Tiling t(TileKind::Corner, c, a.rows, a.cols, true);
    t.cells = a.cells;
    EXPECT_TRUE(validate(t).packing) << "C=" << c << " (" << a.how << ")";
  }
  EXPECT_THROW(no_db(TileKind::Corner, 0), InputError);
}

TEST(AtlasLookup, DirectStochasticTilingIsValidAndMapsIntoTheAtlas) {
  for (auto [kind, c] : {std::pair{TileKind::Corner, 3u}, std::pair{TileKind::Wang, 4u}}) {
    AtlasLookup a = no_db(kind, c);
    for (HashKind h : {HashKind::Permutation, HashKind::LongPeriod}) {
      const DirectTiling tiling(kind, c, h, 7);
      // A 12x12 window of the virtual texture (across negative coordinates) is a valid tiling;
      // y grows to the south, as grid rows do.
      Tiling t(kind, c, 12, 12, false);
      for (int r = 0; r < 12; ++r)
        for (int x = -6; x < 6; ++x) t.at(r, x + 6) = tiling.tile(x, r - 6);
      ValidationReport rep = validate(t);
      EXPECT_TRUE(rep.valid) << kind_name(kind) << ": " << (rep.errors.empty() ? "" : rep.errors[0]);
      std::mt19937_64 rng(3);
      std::uniform_real_distribution<double> U(-300, 300);
      for (int i = 0; i < 500; ++i) {
        const double u = U(rng), v = U(rng);
        auto [au, av] = virtual_to_atlas(a, tiling, u, v);
        ASSERT_GE(au, 0.0);
        ASSERT_LT(au, 1.0);
        ASSERT_GE(av, 0.0);
        ASSERT_LT(av, 1.0);
        const int col = int(au * a.cols), row = int(av * a.rows);
        EXPECT_EQ(a.cells[std::size_t(row * a.cols + col)],
                  tiling.tile(std::int64_t(std::floor(u)), std::int64_t(std::floor(v))));
      }
    }
  }
  EXPECT_THROW(virtual_to_atlas(no_db(TileKind::Corner, 3), DirectTiling(TileKind::Corner, 2, HashKind::Permutation, 1),
                                0.5, 0.5),
               InputError);
}

TEST(AtlasLookup, CHeaderCompilesAndItsTablesAreInverse) {
  TempDir d;
  AtlasLookup a = no_db(TileKind::Corner, 5);
  write_text(d / "atlas.h", lookup_c_header(a));
  write_text(d / "main.c",
             "#include \"atlas.h\"\n"
             "int main(void) {\n"
             "  for (unsigned t = 0; t < TILEKIT_CORNER_5_TILES; ++t) {\n"
             "    unsigned r = tilekit_corner_5_positions[t][0], c = tilekit_corner_5_positions[t][1];\n"
             "    if (tilekit_corner_5_cells[r * TILEKIT_CORNER_5_COLS + c] != t) return 1;\n"
             "  }\n"
             "  return TILEKIT_CORNER_5_ROWS == 25 ? 0 : 2;\n"
             "}\n");
  ASSERT_EQ(sh("cc -std=c99 -Wall -Werror -o " + (d / "check") + " " + (d / "main.c")), 0);
  EXPECT_EQ(sh(d / "check"), 0);
}

// The closed-form part of the GLSL snippet is plain integer code; compiled as C++ with an
// ivec2 stand-in, it must give the same position as the table for every tile.
TEST(AtlasLookup, GlslClosedFormRunsAndAgreesWithTheTable) {
  for (auto [kind, c] : {std::pair{TileKind::Corner, 7u}, std::pair{TileKind::Wang, 5u}}) {
    TempDir d;
    AtlasLookup a = no_db(kind, c);
    ASSERT_TRUE(a.closed_form);
    const std::string glsl = lookup_glsl(a, DirectTiling(kind, c, HashKind::LongPeriod, 1));
    std::smatch m;
    ASSERT_TRUE(
        std::regex_search(glsl, m, std::regex("// BEGIN tk_tile_position\n([\\s\\S]*)// END tk_tile_position")));
    std::string expected;
    for (const auto& [r, col] : a.positions) expected += std::to_string(r) + " " + std::to_string(col) + "\n";
    write_text(d / "expected.txt", expected);
    write_text(d / "main.cpp",
               "#include <cstdio>\nstruct ivec2 { int x, y; ivec2(int a, int b) : x(a), y(b) {} };\n"
               "#define TK_COLORS " +
                   std::to_string(c) + "\n#define TK_COLS " + std::to_string(a.cols) + "\n" + m[1].str() +
                   "int main() { for (int t = 0; t < " + std::to_string(a.cells.size()) +
                   "; ++t) { ivec2 p = tk_tile_position(t); std::printf(\"%d %d\\n\", p.x, p.y); } }\n");
    ASSERT_EQ(sh("c++ -std=c++17 -o " + (d / "run") + " " + (d / "main.cpp")), 0);
    ASSERT_EQ(sh(d / "run" + " > " + (d / "got.txt")), 0);
    EXPECT_TRUE(slurp(d / "got.txt") == expected) << kind_name(kind);
  }
}

TEST(AtlasLookup, GlslSnippetCompilesAsAFragmentShader) {
  ASSERT_EQ(sh("command -v glslangValidator >/dev/null"), 0) << "glslangValidator missing: run scripts/setup.sh";
  TempDir d;
  Tiling shifted = construct_packing(TileKind::Corner, 3)->tiling;  // table variant via a db-like packing
  AtlasLookup table = lookup_from_packing(shifted, "db", "test", false);
  for (const AtlasLookup& a : {no_db(TileKind::Corner, 5), no_db(TileKind::Wang, 3), table}) {
    write_text(d / "t.frag", "#version 330 core\nin vec2 uv;\nout vec4 color;\n" +
                                 lookup_glsl(a, DirectTiling(a.kind, a.colours, HashKind::Permutation, 9)) +
                                 "void main() { color = vec4(tk_atlas_coord(uv * 64.0), 0.0, 1.0); }\n");
    EXPECT_EQ(sh("glslangValidator " + (d / "t.frag") + " > " + (d / "log.txt") + " 2>&1"), 0) << slurp(d / "log.txt");
  }
}

TEST(AtlasLookup, FastJsonTextEqualsTheJsonObject) {
  for (auto [kind, c] : {std::pair{TileKind::Corner, 3u}, std::pair{TileKind::Wang, 2u}}) {
    AtlasLookup a = no_db(kind, c);
    EXPECT_EQ(lookup_json_text(a), lookup_json(a).dump());
    a.solution_id = 4;
    a.source = "db";
    a.how = "solution \"4\" in x";
    EXPECT_EQ(lookup_json_text(a), lookup_json(a).dump());
  }
}

TEST(AtlasLookup, NonPackingsAreRejected) {
  Tiling t = construct_packing(TileKind::Corner, 3)->tiling;
  std::swap(t.cells[0], t.cells[1]);  // every tile once, but borders no longer match
  EXPECT_THROW(lookup_from_packing(t, "db", "", false), InputError);
  t.cells[0] = t.cells[2];  // a repeated tile
  EXPECT_THROW(lookup_from_packing(t, "db", "", false, false), InputError);
}
