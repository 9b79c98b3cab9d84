// The golden vectors that `texture preview`'s JavaScript must share with the C++
// (tests/render/preview_golden.json), checked here against the C++ itself: SplitMix64 and its
// below (base/random.hpp), derive_seed, FNV-1a (base/hash.hpp), and the permutation tables that
// glsl_hash_uniforms (tiling/direct_tiling_glsl.hpp) gives the shaders and the page's check. The
// same file is checked against the JavaScript by preview_golden.test.js under node (ctest
// PreviewGolden.JavaScript...), so a port that drifts from the C++ fails one side or the other.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "../cli_runner.hpp"
#include "base/hash.hpp"
#include "base/random.hpp"
#include "render/baseline_samplers.hpp"
#include "render/preview_scripts.hpp"
#include "tiling/direct_tiling.hpp"
#include "tiling/direct_tiling_glsl.hpp"

namespace tilekit {
namespace {

const nlohmann::json& golden() {
  static const nlohmann::json g =
      nlohmann::json::parse(test::slurp(std::string(TILEKIT_SOURCE_DIR) + "/tests/render/preview_golden.json"));
  return g;
}

std::uint64_t u64(const nlohmann::json& v) {
  return std::stoull(v.get<std::string>());
}

TEST(PreviewGolden, SplitMix64StreamsBelowAndDeriveSeed) {
  ASSERT_FALSE(golden()["splitmix64"].empty());
  for (const auto& v : golden()["splitmix64"]) {
    SplitMix64 r(u64(v["seed"]));
    for (const auto& want : v["outputs"]) EXPECT_EQ(r.next(), u64(want)) << "seed " << v["seed"];
  }
  ASSERT_FALSE(golden()["below"].empty());
  for (const auto& v : golden()["below"]) {
    SplitMix64 r(u64(v["seed"]));
    for (const auto& want : v["outputs"])
      EXPECT_EQ(r.below(v["n"].get<std::uint64_t>()), want.get<std::uint64_t>()) << "seed " << v["seed"];
  }
  ASSERT_FALSE(golden()["derive_seed"].empty());
  for (const auto& v : golden()["derive_seed"])
    EXPECT_EQ(derive_seed(u64(v["seed"]), v["stream"].get<std::uint64_t>()), u64(v["value"])) << v.dump();
}

TEST(PreviewGolden, Fnv1aOfTextAndBytes) {
  ASSERT_FALSE(golden()["fnv1a"].empty());
  for (const auto& v : golden()["fnv1a"]) {
    std::string bytes;
    if (v.contains("text")) {
      bytes = v["text"].get<std::string>();
    } else {
      for (const auto& b : v["bytes"]) bytes += char(b.get<std::uint8_t>());
    }
    EXPECT_EQ(StableHash().add(std::string_view(bytes)).fnv(), u64(v["hash"])) << v.dump();
  }
}

// The hash a vector's builder names: a direct tiling's (as the tiles method's recipes) or the
// hex/hpn patch hash (PatchHashes, as their recipes), for the vector's seed and the recipe's kind.
TEST(PreviewGolden, PermutationTablesEqualTheShadersUniforms) {
  ASSERT_FALSE(golden()["tables"].empty());
  for (const auto& v : golden()["tables"]) {
    const nlohmann::json& b = v["builder"];
    const nlohmann::json& recipe = v["recipe"];
    const HashKind kind = parse_hash_kind(recipe["kind"].get<std::string>());
    const std::uint64_t seed = u64(v["seed"]);
    std::vector<std::int32_t> table;
    std::vector<std::uint32_t> sizes;
    const auto take = [&](const ColourHash& h) {
      table = glsl_hash_uniforms(h);
      for (const ColourHash::Component& c : h.components()) sizes.push_back(c.n);
      EXPECT_EQ(hash_kind_name(h.kind()), recipe["kind"].get<std::string>()) << b.dump();
    };
    if (b.contains("tiling")) {
      const DirectTiling tiling(b["tiling"] == "wang" ? TileKind::Wang : TileKind::Corner,
                                b["colors"].get<std::uint32_t>(), kind, seed);
      const std::size_t index = b["index"].get<std::size_t>();
      ASSERT_LT(index, tiling.hashes().size()) << b.dump();
      take(*tiling.hashes()[index]);
      // The page's recipe for it (render/preview.cpp): a corner tiling's one hash takes the seed
      // itself, a Wang tiling's hash k derives stream k + 1.
      EXPECT_EQ(recipe["streams"], b["tiling"] == "wang" ? nlohmann::json::array({index + 1}) : nlohmann::json::array())
          << b.dump();
    } else {
      const PatchHashes h(kind, seed);
      take(b["patch"] == "x" ? h.x : h.y);
      EXPECT_EQ(recipe["streams"], nlohmann::json::array({b["patch"] == "x" ? 1 : 2})) << b.dump();
    }
    EXPECT_EQ(recipe["sizes"], nlohmann::json(sizes)) << b.dump();
    EXPECT_EQ(nlohmann::json(table), v["table"]) << b.dump();
  }
}

// What node tests is what the page embeds: both scripts, byte for byte.
TEST(PreviewGolden, ThePageEmbedsTheScriptFilesThatNodeTests) {
  std::vector<std::string> names;
  for (const EmbeddedFile& f : preview_scripts()) {
    names.emplace_back(f.name);
    EXPECT_EQ(std::string(f.text), test::slurp(std::string(TILEKIT_SOURCE_DIR) + "/render/" + std::string(f.name)))
        << f.name;
  }
  EXPECT_EQ(names, (std::vector<std::string>{"preview.js", "preview_tables.js"}));
}

}  // namespace
}  // namespace tilekit
