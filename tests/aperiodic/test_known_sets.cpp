// The collection of sets with a known status (aperiodic/data/README.md), decided by the
// transducer method: every periodic set periodic with a validated witness, every finite set
// finite, and no aperiodic set (the published ones, the thesis' sound conversions) ever
// periodic or finite.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>

#include "aperiodic/canonical.hpp"
#include "aperiodic/conversion.hpp"
#include "aperiodic/decide.hpp"
#include "aperiodic/smallest.hpp"
#include "tests/build_paths.hpp"
#include "tilesets/tile_set_io.hpp"
#include "tilesets/validator.hpp"

using namespace tilekit;

namespace {

struct Known {
  std::string path, status;
  bool slow = false;  // "# expect: unknown": beyond the method in the time given here
};

std::vector<Known> collection() {
  std::vector<Known> out;
  for (const auto& e : std::filesystem::directory_iterator(std::string(TILEKIT_SOURCE_DIR) + "/aperiodic/data")) {
    if (e.path().extension() != ".tiles") continue;
    Known k{e.path().string(), "", false};
    std::ifstream in(e.path());
    static const std::regex status(R"(^#\s*status:\s*(\w+))"), expect(R"(^#\s*expect:\s*unknown)");
    std::smatch m;
    for (std::string line; std::getline(in, line);) {
      if (std::regex_search(line, m, status)) k.status = m[1];
      if (std::regex_search(line, expect)) k.slow = true;
    }
    out.push_back(k);
  }
  std::sort(out.begin(), out.end(), [](const Known& a, const Known& b) { return a.path < b.path; });
  return out;
}

DecideResult decide(const TileSet& s, double seconds) {
  DecideOptions o;
  o.time_limit = seconds;
  return decide_tile_set(s, o);
}

}  // namespace

TEST(KnownSets, EveryPeriodicSetIsPeriodicAndEveryFiniteSetFinite) {
  auto all = collection();
  ASSERT_GE(all.size(), 10u);
  int periodic = 0, finite = 0;
  for (const Known& k : all) {
    TileSet s = read_tile_set_file(k.path);
    DecideResult r = decide(s, k.slow ? 0.5 : 10);
    if (k.status == "periodic") {
      ++periodic;
      ASSERT_EQ(r.verdict, "periodic") << k.path;
      ASSERT_TRUE(r.witness_tiling) << k.path;
      EXPECT_TRUE(r.witness_validated) << k.path;
      EXPECT_TRUE(validate(*r.witness_tiling, &s).valid) << k.path;
      EXPECT_EQ(r.witness.size(), std::size_t(r.period_rows));
    } else if (k.status == "finite") {
      ++finite;
      EXPECT_NE(r.verdict, "periodic") << k.path;
      if (!k.slow) {
        EXPECT_EQ(r.verdict, "finite") << k.path;
      }
      if (r.verdict == "finite") {
        EXPECT_GT(r.square_bound_log10, 0) << k.path;
      }
    } else {
      ADD_FAILURE() << k.path << ": unknown status '" << k.status << "'";
    }
  }
  EXPECT_GE(periodic, 7);
  EXPECT_GE(finite, 2);
}

TEST(KnownSets, NoAperiodicSetIsEverPeriodicOrFinite) {
  std::vector<TileSet> sets;
  for (const std::string& name : published_aperiodic_sets()) sets.push_back(resolve_tile_set(name));
  for (const char* v : {"jeandel-rao-11-variant-2", "jeandel-rao-11-variant-3"}) sets.push_back(resolve_tile_set(v));
  // The thesis' sound conversions (conjugate, or lifts after pruning) and the smallest chain.
  for (auto [name, m] : {std::pair{"culik-13", ConversionMethod::Diagonal},
                         {"kari-14", ConversionMethod::Vertical},
                         {"labbe-19", ConversionMethod::Vertical},
                         {"ammann-gs-16", ConversionMethod::Rotation},
                         {"jeandel-rao-11", ConversionMethod::Subdivision}}) {
    LabelledConversion c = build_conversion(resolve_tile_set(name), {m, {}, -1});
    ASSERT_TRUE(c.soundness == Soundness::Conjugate || c.soundness == Soundness::Lifts) << name;
    sets.push_back(c.set);
  }
  sets.push_back(smallest_aperiodic_corner_set().set);
  for (const TileSet& s : sets) {
    DecideResult r = decide(s, 0.4);
    EXPECT_EQ(r.verdict, "unknown") << s.name();
    EXPECT_GT(r.k, 1) << s.name();
  }
}

// finite-212 (Jeandel & Rao) and finite-256 (Jeandel & Vanier) are one tile set: the same
// canonical form up to symmetry and colour names (finite-256 is finite-212 with its colours
// renamed), so they share one largest square and the transducer counts are equal level by level.
TEST(KnownSets, Finite212AndFinite256AreOneSetUpToColourNames) {
  const std::string dir = std::string(TILEKIT_SOURCE_DIR) + "/aperiodic/data/";
  const CanonicalForm a = canonical_form(read_tile_set_file(dir + "finite-212.tiles"));
  const CanonicalForm b = canonical_form(read_tile_set_file(dir + "finite-256.tiles"));
  ASSERT_TRUE(a.exact && b.exact);
  EXPECT_EQ(a.hash, b.hash);
  EXPECT_EQ(a.text, b.text);
  // Not every pair is equal: finite-14 is another set.
  EXPECT_NE(canonical_form(read_tile_set_file(dir + "finite-14.tiles")).hash, a.hash);
}
