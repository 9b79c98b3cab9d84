// The transducer method (aperiodic/transducer.hpp, chain.hpp, decide.hpp): its operations, its
// verdicts on sets built to be periodic or finite, its witnesses and its checkpoints.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <tuple>

#include "aperiodic/chain.hpp"
#include "aperiodic/decide.hpp"
#include "aperiodic/decide_checkpoint.hpp"
#include "aperiodic/generate.hpp"
#include "aperiodic/transducer.hpp"
#include "base/error.hpp"
#include "checkpoints/checkpoint.hpp"
#include "tests/cli_runner.hpp"
#include "tilesets/tile_set_io.hpp"
#include "tilesets/validator.hpp"

using namespace tilekit;

namespace {

// Tiles (i, j), i < p, j < q, whose colours encode the position mod (p, q): they tile only the
// p x q periodic pattern (and its translates).
TileSet torus_set(int p, int q) { return torus_with_decoys(p, q, 0, 0); }

DecideOptions quick(double seconds = 5) {
  DecideOptions o;
  o.time_limit = seconds;
  return o;
}

}  // namespace

TEST(Transducer, BisimilarStatesMergeAndCyclesOutsideComponentsAreTrimmed) {
  // States 0 and 1 both loop on (a|a) and go to each other: forward bisimilar. State 2 only
  // enters the component (2 -> 0) and is trimmed.
  Transducer t;
  t.states = 3;
  t.transitions = {{0, 0, 0, 0}, {1, 0, 0, 1}, {0, 1, 1, 1}, {1, 1, 1, 0}, {2, 0, 0, 0}};
  t.finalize();
  std::size_t components = 0;
  auto renum = trim_to_components(t, &components);
  EXPECT_EQ(components, 2u);
  EXPECT_EQ(renum[2], kNoState);
  EXPECT_EQ(t.states, 2u);
  EXPECT_EQ(t.transitions.size(), 4u);
  auto cls = merge_bisimilar(t, true);
  EXPECT_EQ(cls[0], cls[1]);
  EXPECT_EQ(t.states, 1u);
  EXPECT_EQ(t.transitions.size(), 2u);  // (a|a) and (b|b) loops
  EXPECT_EQ(find_periodic_cycle(t).size(), 1u);
}

TEST(Transducer, CompositionReadsTheLowerRowAndWritesTheUpperOne) {
  // One state, transitions 0|1 and 1|0: two rows compose to the identity on {0, 1}.
  Transducer t;
  t.states = 1;
  t.transitions = {{0, 0, 1, 0}, {0, 1, 0, 0}};
  t.finalize();
  Product p = compose(t, t, 2);
  ASSERT_EQ(p.t.transitions.size(), 2u);
  for (const Transition& e : p.t.transitions) EXPECT_EQ(e.in, e.out);
}

TEST(Decide, ASetBuiltToBePeriodicIsPeriodicWithItsLeastPeriods) {
  for (auto [p, q] : {std::pair{2, 3}, {5, 1}, {1, 7}, {4, 6}}) {
    TileSet s = torus_set(p, q);
    DecideResult r = decide_tile_set(s, quick());
    ASSERT_EQ(r.verdict, "periodic") << p << "x" << q;
    EXPECT_EQ(r.period_rows, p);
    EXPECT_EQ(r.period_cols, q);
    ASSERT_TRUE(r.witness_tiling);
    EXPECT_TRUE(r.witness_validated);
    EXPECT_TRUE(validate(*r.witness_tiling, &s).valid);
  }
}

TEST(Decide, BothDirectionsFindTheSamePeriodicSet) {
  TileSet s = torus_set(3, 5);
  for (bool columns : {false, true}) {
    DecideOptions o = quick();
    o.rows = !columns;
    o.columns = columns;
    DecideResult r = decide_tile_set(s, o);
    ASSERT_EQ(r.verdict, "periodic");
    EXPECT_EQ(r.direction, columns ? "columns" : "rows");
    EXPECT_EQ(r.k, columns ? 5 : 3);  // the least period in the chain's direction
    EXPECT_TRUE(validate(*r.witness_tiling, &s).valid);
  }
}

TEST(Decide, ARowThatNeverStacksIsFiniteWithASquareBound) {
  TileSet s = parse_tile_set("0 1 0 0\n", "row.tiles");  // n=0, s=1: no tile fits above it
  DecideResult r = decide_tile_set(s, quick());
  EXPECT_EQ(r.verdict, "finite");
  ASSERT_TRUE(r.square_bound);
  EXPECT_GE(*r.square_bound, 1u);  // a 1x1 square is tileable
}

TEST(Decide, TheSquareBoundOfAFiniteSetIsAtLeastTheLargestTileableSquare) {
  // Jeandel & Vanier's 7 tiles tile a 14 x 14 square (aperiodic/data/finite-14.tiles).
  TileSet s = read_tile_set_file(std::string(TILEKIT_SOURCE_DIR) + "/aperiodic/data/finite-14.tiles");
  DecideResult r = decide_tile_set(s, quick(20));
  ASSERT_EQ(r.verdict, "finite");
  ASSERT_GT(r.square_bound_log10, 0);
  if (r.square_bound) {
    EXPECT_GE(*r.square_bound, 14u);
  }
}

TEST(Decide, MergingChangesNoVerdictAndNoPeriodFoundInOneDirection) {
  for (const char* name : {"periodic-7-30", "finite-14", "periodic-9-73"}) {
    TileSet s = read_tile_set_file(std::string(TILEKIT_SOURCE_DIR) + "/aperiodic/data/" + name + ".tiles");
    for (bool columns : {false, true}) {
      DecideOptions merged = quick(20);
      merged.rows = !columns;
      merged.columns = columns;
      DecideOptions plain = merged;
      plain.merge = false;
      DecideResult a = decide_tile_set(s, merged), b = decide_tile_set(s, plain);
      EXPECT_EQ(a.verdict, b.verdict) << name;
      EXPECT_EQ(a.k, b.k) << name;  // the same least k in one direction
      EXPECT_EQ(a.shift, b.shift) << name;
      for (std::size_t i = 0; i < a.levels.size() && i < b.levels.size(); ++i)
        EXPECT_LE(a.levels[i].states, b.levels[i].states) << name;  // merging only shrinks
    }
  }
}

TEST(Decide, TorusSetsWithDecoysUpToAHundredTilesArePeriodic) {
  for (auto [p, q, d] : {std::tuple{7, 9, 20}, {5, 5, 75}, {3, 11, 40}}) {
    TileSet s = torus_with_decoys(p, q, d, 12);
    ASSERT_EQ(s.size(), std::size_t(p * q + d));
    DecideResult r = decide_tile_set(s, quick(20));
    ASSERT_EQ(r.verdict, "periodic") << s.name();
    EXPECT_TRUE(validate(*r.witness_tiling, &s).valid);
  }
}

TEST(Decide, AnAperiodicSetStaysUnknownAndTheTimeLimitHolds) {
  TileSet s = resolve_tile_set("jeandel-rao-11");
  auto t0 = std::chrono::steady_clock::now();
  DecideResult r = decide_tile_set(s, quick(0.5));
  double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_EQ(r.verdict, "unknown");
  EXPECT_EQ(r.stopped_by, "time-limit");
  EXPECT_GT(r.k, 1);
  EXPECT_LT(secs, 1.5);
  EXPECT_EQ(r.levels.size(), std::size_t(r.k_rows + r.k_columns));
}

TEST(Decide, MaxKStopsEachDirectionThere) {
  DecideOptions o = quick();
  o.max_k = 4;
  DecideResult r = decide_tile_set(resolve_tile_set("kari-14"), o);
  EXPECT_EQ(r.verdict, "unknown");
  EXPECT_EQ(r.stopped_by, "max-k");
  EXPECT_EQ(r.k_rows, 4);
  EXPECT_EQ(r.k_columns, 4);
}

TEST(Decide, CornerSetsAreDecidedThroughTheirWangSet) {
  // complete-corner-1 is one tile: periodic 1x1.
  TileSet s = resolve_tile_set("complete-corner-1");
  DecideResult r = decide_tile_set(s, quick());
  ASSERT_EQ(r.verdict, "periodic");
  EXPECT_EQ(r.witness_tiling->kind, TileKind::Corner);
  EXPECT_TRUE(validate(*r.witness_tiling, &s).valid);
}

TEST(DecideCheckpoint, AResumedRunEndsWhereAStraightRunEnds) {
  test::TempDir d;
  TileSet s = resolve_tile_set("culik-13");
  DecideOptions first = quick();
  first.max_k = 3;
  first.checkpoint_path = d / "c.ckpt";
  DecideResult a = decide_tile_set(s, first);
  ASSERT_EQ(a.checkpoints, 1u);
  DecideOptions second = quick();
  second.max_k = 5;
  second.resume_path = d / "c.ckpt";
  DecideResult b = decide_tile_set(s, second);
  DecideOptions straight = quick();
  straight.max_k = 5;
  DecideResult c = decide_tile_set(s, straight);
  EXPECT_TRUE(b.resumed);
  ASSERT_EQ(b.levels.size(), c.levels.size());
  for (std::size_t i = 0; i < b.levels.size(); ++i) {
    EXPECT_EQ(b.levels[i].k, c.levels[i].k);
    EXPECT_EQ(b.levels[i].transitions, c.levels[i].transitions);
    EXPECT_EQ(b.levels[i].states, c.levels[i].states);
  }
}

TEST(DecideCheckpoint, CorruptForeignOrTruncatedCheckpointsAreInputErrors) {
  test::TempDir d;
  TileSet s = resolve_tile_set("culik-13");
  DecideOptions o = quick();
  o.max_k = 2;
  o.checkpoint_path = d / "c.ckpt";
  decide_tile_set(s, o);
  std::string text = test::slurp(d / "c.ckpt");
  auto resume = [&](const std::string& body, const TileSet& set) {
    test::write_text(d / "x.ckpt", body);
    DecideOptions r = quick();
    r.max_k = 3;
    r.resume_path = d / "x.ckpt";
    return decide_tile_set(set, r);
  };
  EXPECT_THROW(resume(text.substr(0, text.size() - 5), s), InputError);
  std::string flipped = text;
  flipped[flipped.size() - 3] ^= 1;
  EXPECT_THROW(resume(flipped, s), InputError);
  EXPECT_THROW(resume(text, resolve_tile_set("kari-14")), InputError);  // another set
  EXPECT_NO_THROW(resume(text, s));
}

// A level whose count of states is damaged (far beyond its transitions) is refused before the
// index of transitions by state is sized by it (a fuzzed checkpoint spent seconds there).
TEST(DecideCheckpoint, AStateCountBeyondTheTransitionsIsRefusedAtOnce) {
  test::TempDir d;
  const TileSet s = resolve_tile_set("culik-13");
  DecideOptions o = quick();
  o.max_k = 2;
  o.columns = true, o.rows = false;
  o.checkpoint_path = d / "c.ckpt";
  decide_tile_set(s, o);
  const std::string text = test::slurp(d / "c.ckpt");
  const DecideCheckpoint c = decode_decide_checkpoint(text, s.wang_tiles(), "c.ckpt");
  ASSERT_EQ(c.chains.size(), 1u);
  ASSERT_GE(c.chains[0].k(), 2);
  const ChainLevel& level = c.chains[0].level(2);
  // The level's record begins with its states (4 bytes) and its transitions' count (8 bytes).
  auto bytes = [](std::uint64_t v, int n) {
    std::string b;
    for (int i = 0; i < n; ++i) b.push_back(char((v >> (8 * i)) & 0xff));
    return b;
  };
  std::string body(open_checkpoint(text, "TILEKIT-DECIDE", kDecideCheckpointVersion, kDecideCheckpointVersion, "c"));
  const std::string record = bytes(level.t.states, 4) + bytes(level.t.transitions.size(), 8);
  const std::size_t at = body.rfind(record);
  ASSERT_NE(at, std::string::npos);
  body.replace(at, 4, bytes(0xfffffff0u, 4));
  const std::string damaged = seal_checkpoint("TILEKIT-DECIDE", kDecideCheckpointVersion, body);
  const auto t0 = std::chrono::steady_clock::now();
  try {
    decode_decide_checkpoint(damaged, s.wang_tiles(), "damaged.ckpt");
    ADD_FAILURE() << "a damaged state count was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("more states than transitions"), std::string::npos) << e.what();
  }
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 2.0);
}
