// Colour-quotient lifts in the engine: the spec, the model against a brute-force
// filter by the independent validator, counts, first packings by the engine and by cadical.
#include <gtest/gtest.h>

#include <functional>
#include <set>

#include "base/error.hpp"
#include "solver/colour_lift_model.hpp"
#include "solver/sat_cnf.hpp"
#include "solver/solve.hpp"
#include "tilesets/construct_internal.hpp"
#include "tilesets/constructions.hpp"
#include "tilesets/validator.hpp"

using namespace tilekit;

namespace {

SearchResult solve_lift(TileKind kind, std::uint32_t colours, const std::string& spec, SearchMode mode,
                        const std::string& formulation = "auto", int threads = 1) {
  SearchOptions o;
  o.mode = mode;
  o.lift = spec;
  o.formulation = formulation_from_name(formulation).value();
  o.run.threads = threads;  // seed 0: the natural value order first (finds C=4 in milliseconds)
  return solve(complete_packing_problem(kind, colours), o);
}

// The binary lift quotient of period 4 translated (by multiples of 4) so that tile 0 is at (0,0),
// as the model fixes it.
std::vector<Colour> quotient_with_tile_zero_at_origin() {
  const int P = 4, n = 16;
  const std::vector<Colour> e = binary_lift_quotient_pegs(P);
  const Tiling q = corner_torus_from_pegs(e, n, n, 2);
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 4; ++b)
      if (q.at(P * a, P * b) == 0) {
        std::vector<Colour> t(e.size());
        for (int r = 0; r < n; ++r)
          for (int c = 0; c < n; ++c) t[std::size_t(r * n + c)] = e[std::size_t(((r + P * a) % n) * n + (c + P * b) % n)];
        return t;
      }
  return {};
}

}  // namespace

TEST(LiftSpec, ParsesTheBaseColourCountAndFile) {
  EXPECT_EQ(parse_lift_spec("4").base_colours, 4u);
  LiftSpec s = parse_lift_spec("m=2,base=b.json");
  EXPECT_EQ(s.base_colours, 2u);
  EXPECT_EQ(s.base_file, "b.json");
  EXPECT_EQ(s.text(), "m=2,base=b.json");
  for (const char* bad : {"", "m=0", "x", "4,q=1", "m=4,base=", "m=4,base", "base"}) EXPECT_THROW(parse_lift_spec(bad), InputError) << bad;
}

TEST(LiftProblem, NeedsAMultipleOfTheBaseColours) {
  LiftProblem p = make_lift_problem(TileKind::Corner, 8, parse_lift_spec("4"));
  EXPECT_EQ(p.quotient_colours, 2u);
  EXPECT_EQ(p.period, 16);
  EXPECT_EQ(p.quotient.rows, 64);
  EXPECT_THROW(make_lift_problem(TileKind::Corner, 6, parse_lift_spec("4")), InputError);
  EXPECT_THROW(make_lift_problem(TileKind::Corner, 4, parse_lift_spec("4")), InputError);  // k = 1
  EXPECT_THROW(make_lift_problem(TileKind::Corner, 8, parse_lift_spec("m=4,base=/nonexistent.json")), InputError);
}

TEST(LiftModel, OneColourBaseCountsThePlainPackings) {
  // m = 1: the quotient is itself a packing, so the lift subspace is everything.
  SearchResult corner = solve_lift(TileKind::Corner, 2, "1", SearchMode::Count);
  EXPECT_TRUE(corner.complete);
  EXPECT_EQ(corner.solutions, 32u);
  EXPECT_EQ(corner.formulation, "lift");
}

TEST(LiftModel, AllModeEmitsEveryPackingOnceAndValid) {
  SearchOptions o;
  o.mode = SearchMode::All;
  o.lift = "1";
  std::set<std::vector<TileIndex>> seen;
  o.on_solution = [&](const Tiling& t) {
    EXPECT_TRUE(validate(t).packing);
    seen.insert(t.cells);
  };
  SearchResult r = solve(complete_packing_problem(TileKind::Corner, 2), o);
  EXPECT_EQ(r.solutions, 32u);
  EXPECT_EQ(seen.size(), 32u);
}

TEST(LiftModel, CompletionsEqualTheValidatorFilterOnTheLiftedPacking) {
  // C = 4 over the stored C = 2 packing (period 4, 16x16 binary quotient). Fix all but the last
  // F variables of the model's order to a known quotient; the engine's completions must be
  // exactly the assignments of those F pegs whose lift the independent validator accepts.
  const LiftProblem lp = make_lift_problem(TileKind::Corner, 4, parse_lift_spec("2"));
  const std::vector<Colour> pegs = quotient_with_tile_zero_at_origin();
  ASSERT_FALSE(pegs.empty());
  const LiftModel root = lift_lattice_model(lp);
  std::vector<int> order, values;
  {
    LiftModel probe = root;
    for (int var; (var = probe.branch(values)) >= 0;) {
      order.push_back(var);
      ASSERT_TRUE(probe.assign(var, int(pegs[std::size_t(var)]))) << "the known quotient fails at var " << var;
    }
    EXPECT_TRUE(validate(probe.tiling()).packing);
  }
  const std::size_t F = 14, prefix = order.size() - F;
  LiftModel start = root;
  for (std::size_t i = 0; i < prefix; ++i) ASSERT_TRUE(start.assign(order[i], int(pegs[std::size_t(order[i])])));
  std::uint64_t engine = 0;
  std::function<void(LiftModel&)> dfs = [&](LiftModel& m) {
    std::vector<int> vals;
    const int var = m.branch(vals);
    if (var < 0) {
      ASSERT_TRUE(validate(m.tiling()).packing);
      ++engine;
      return;
    }
    for (int v : vals) {
      if (m.assign(var, v)) dfs(m);
      m.unassign(var, v);
    }
  };
  dfs(start);
  std::uint64_t filter = 0;
  for (std::uint32_t mask = 0; mask < (1u << F); ++mask) {
    std::vector<Colour> q = pegs;
    for (std::size_t j = 0; j < F; ++j) q[std::size_t(order[prefix + j])] = (mask >> j) & 1;
    filter += validate(colour_lift(lp.base, corner_torus_from_pegs(q, 16, 16, 2))).packing;
  }
  EXPECT_GE(filter, 1u);
  EXPECT_EQ(engine, filter);
}

TEST(LiftModel, FindsFourColourCornerAndWangPackingsOverTwoColours) {
  for (TileKind kind : {TileKind::Corner, TileKind::Wang}) {
    SearchResult r = solve_lift(kind, 4, "2", SearchMode::First, "auto", 2);
    ASSERT_EQ(r.found.size(), 1u) << kind_name(kind);
    EXPECT_TRUE(validate(r.found[0]).packing) << kind_name(kind);
    // The packing is a lift of the base: its colours mod 2 repeat the base with period 4.
    const Tiling base = construct_packing(kind, 2)->tiling;
    for (int row = 0; row < 16; ++row)
      for (int c = 0; c < 16; ++c) {
        const TileIndex t = r.found[0].at(row, c), b = base.at(row % 4, c % 4);
        if (kind == TileKind::Corner) {
          const CornerTile x = corner_tile(t, 4), y = corner_tile(b, 2);
          ASSERT_TRUE(x.ne % 2 == y.ne && x.se % 2 == y.se && x.sw % 2 == y.sw && x.nw % 2 == y.nw);
        } else {
          const WangTile x = wang_tile(t, 4), y = wang_tile(b, 2);
          ASSERT_TRUE(x.n % 2 == y.n && x.e % 2 == y.e && x.s % 2 == y.s && x.w % 2 == y.w);
        }
      }
  }
}

TEST(LiftSat, FindsAFourColourPackingWithCadical) {
  if (!sat_solver_available()) GTEST_SKIP() << "cadical not installed (scripts/setup.sh installs it)";
  SearchResult r = solve_lift(TileKind::Corner, 4, "2", SearchMode::First, "sat");
  ASSERT_EQ(r.found.size(), 1u);
  EXPECT_EQ(r.formulation, "sat");
  EXPECT_TRUE(validate(r.found[0]).packing);
  EXPECT_THROW(solve_lift(TileKind::Corner, 4, "2", SearchMode::Count, "sat"), InputError);
}

TEST(LiftSat, EightColourBinaryLiftHasAboutSeventyThousandPrimaryVariables) {
  std::uint64_t vars = 0, clauses = 0;
  lift_cnf(make_lift_problem(TileKind::Corner, 8, parse_lift_spec("4")), &vars, &clauses);
  // 4096 pegs + 4096 cells x 16 windows, plus the at-most-one counters.
  EXPECT_GT(vars, 4096u + 65536u);
  EXPECT_LT(vars, 4u * (4096u + 65536u));
  EXPECT_GT(clauses, 65536u);
}
