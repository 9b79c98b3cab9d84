// The smallest corner set (aperiodic/smallest.hpp): the chain an enumeration recorded is
// re-derived link by link and checked; records are parsed strictly; a search's record round-trips.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "aperiodic/enumerate.hpp"
#include "aperiodic/smallest.hpp"
#include "aperiodic/steps.hpp"
#include "base/error.hpp"

using namespace tilekit;

namespace {

std::string record_text(const std::string& source, const std::string& steps, const std::string& set) {
  return R"({"format": "tilekit-smallest-chain", "command": "tilekit aperiodic enumerate", "digest": "0",
             "complete": true, "expanded": 1, "sets": 1, "source": ")" +
         source + R"(", "steps": )" + steps + R"(, "set": ")" + set + R"(", "tiles": 26, "colors": 4})";
}

}  // namespace

TEST(SmallestSet, TheEmbeddedRecordReDerivesToASoundCornerSetBelowThePublishedRecord) {
  const RecordedChain rec = embedded_smallest_record();
  EXPECT_EQ(rec.command.rfind("tilekit aperiodic enumerate", 0), 0u) << rec.command;
  EXPECT_TRUE(rec.complete);
  const CornerSetCandidate c = rederive_chain(rec);
  EXPECT_EQ(c.set.kind(), TileKind::Corner);
  EXPECT_EQ(c.tiles, rec.tiles);
  EXPECT_LE(c.tiles, 29u);  // Nurmi 2016 published 30
  EXPECT_EQ(c.chain.back().set, rec.set);
  ASSERT_EQ(c.chain.size(), rec.steps.size() + 1);
  EXPECT_EQ(c.chain.front().label, "published");
  for (const ChainStep& s : c.chain) EXPECT_TRUE(sound_label(s.label)) << s.step << " " << s.label;
}

TEST(SmallestSet, ARecordThatNoLongerReDerivesIsRefused) {
  const RecordedChain rec = embedded_smallest_record();
  RecordedChain wrong = rec;
  wrong.set = "0123456789abcdef";
  // Every refusal is an InputError naming the link that does not re-derive.
  auto refused_link = [](const RecordedChain& r) {
    try {
      rederive_chain(r);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(refused_link(wrong).find("link " + std::to_string(rec.steps.size())), std::string::npos)
      << refused_link(wrong);
  RecordedChain wang = rec;
  wang.steps.clear();  // the published Wang set itself: not a corner set
  wang.set = replay_chain(rec.source, {}).front().hash;
  EXPECT_NE(refused_link(wang).find("link 0 (the source"), std::string::npos) << refused_link(wang);
  RecordedChain tiles = rec;
  ++tiles.tiles;  // the right set, the wrong size
  EXPECT_NE(refused_link(tiles).find("tiles"), std::string::npos) << refused_link(tiles);
  RecordedChain unknown = rec;
  unknown.source = "penrose-2";
  EXPECT_THROW(rederive_chain(unknown), InputError);
  RecordedChain bad_step = rec;
  bad_step.steps = {"squash"};
  EXPECT_THROW(rederive_chain(bad_step), InputError);
}

TEST(SmallestSet, MalformedRecordsAreInputErrors) {
  EXPECT_NO_THROW(parse_smallest_record(record_text("kari-14", "[\"prune\"]", "x"), "r.json"));
  EXPECT_THROW(parse_smallest_record("not json", "r.json"), InputError);
  EXPECT_THROW(parse_smallest_record("{}", "r.json"), InputError);
  EXPECT_THROW(parse_smallest_record(record_text("kari-14", "\"prune\"", "x"), "r.json"), InputError);
  EXPECT_THROW(parse_smallest_record(record_text("kari-14", "[1]", "x"), "r.json"), InputError);
  std::string other = record_text("kari-14", "[]", "x");
  other.replace(other.find("tilekit-smallest-chain"), 22, "tilekit-enumerate");
  EXPECT_THROW(parse_smallest_record(other, "r.json"), InputError);
}

TEST(SmallestSet, ASearchsRecordRoundTripsAndReDerives) {
  EnumerateOptions o;
  o.sources = {"jeandel-rao-11-variant-2"};
  o.max_depth = 1;
  o.max_tiles = 100;
  const EnumerateResult r = enumerate_conversions(o);
  const RecordedChain rec = parse_smallest_record(smallest_record("rerun me", r).dump(), "search");
  EXPECT_EQ(rec.source, "jeandel-rao-11-variant-2");
  EXPECT_EQ(rec.command, "rerun me");
  EXPECT_EQ(rec.digest, r.digest);
  ASSERT_EQ(rec.steps.size(), 1u);
  const CornerSetCandidate c = rederive_chain(rec);
  EXPECT_EQ(c.chain.back().set, rec.set);
  EXPECT_EQ(c.tiles, rec.tiles);
  // A search that reaches no corner set has nothing to record.
  o.max_depth = 0;
  EXPECT_THROW(smallest_record("rerun me", enumerate_conversions(o)), NotFound);
}
