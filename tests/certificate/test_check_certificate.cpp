// The independent certificate checker (certificate/check.hpp) on the checked-in certificate of the
// 25-tile corner set (certificate/data/smallest-25.json, what `aperiodic certify` writes): accepted
// as it is; rejected with one recovery entry changed, with the radius lowered to 1, with a radius-1
// table, with a source tile changed and with a prune round that removes a tile some patch needs.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "certificate/check.hpp"
#include "tests/build_paths.hpp"
#include "tilesets/tile_set_io.hpp"

namespace {

using tilekit::certificate::Tile;

nlohmann::json smallest_certificate(const std::string& name = "smallest-25.json") {
  std::ifstream in(std::string(tilekit::test::source_dir()) + "/certificate/data/" + name);
  std::stringstream s;
  s << in.rdbuf();
  return nlohmann::json::parse(s.str());
}

std::vector<Tile> published(const std::string& name) {
  std::vector<Tile> out;
  const tilekit::TileSet set = tilekit::resolve_tile_set(name);
  for (const tilekit::WangTile& t : set.wang_tiles()) out.push_back({t.n, t.e, t.s, t.w});
  return out;
}

nlohmann::json& merge_link(nlohmann::json& cert) {
  for (auto& l : cert["links"])
    if (l["op"] == "merge") return l;
  throw std::logic_error("no merge link");
}

const std::vector<Tile>& source_tiles() {
  static const std::vector<Tile> t = published("jeandel-rao-11-variant-2");
  return t;
}

TEST(CertificateCheck, AcceptsTheSmallestSetsCertificate) {
  nlohmann::json cert = smallest_certificate();
  const tilekit::certificate::Report r = tilekit::certificate::check(cert, source_tiles());
  ASSERT_TRUE(r.accepted) << r.error;
  EXPECT_TRUE(r.source_matches_reference);
  EXPECT_EQ(r.source, "jeandel-rao-11-variant-2");
  EXPECT_EQ(r.source_tiles, 11u);
  EXPECT_EQ(r.result_tiles, 25u);
  EXPECT_EQ(r.result_colours, 5u);
  // blocks, to-wang, translation and merge, with symmetries between them.
  std::vector<std::string> ops;
  for (const auto& l : r.links)
    if (l.op != "symmetry") ops.push_back(l.op);
  EXPECT_EQ(ops, (std::vector<std::string>{"blocks", "to-wang", "translation", "merge"}));
  EXPECT_EQ(merge_link(cert)["radius"], 2);
}

// The 24-tile set: the 25-set's chain, then to-wang, horizontal+prune5 and merge-colours again.
TEST(CertificateCheck, AcceptsTheTwentyFourSetsCertificate) {
  const auto r = tilekit::certificate::check(smallest_certificate("smallest-24.json"), source_tiles());
  ASSERT_TRUE(r.accepted) << r.error;
  EXPECT_EQ(r.result_tiles, 24u);
  EXPECT_EQ(r.result_colours, 4u);
}

TEST(CertificateCheck, RejectsOneRecoveryEntryChanged) {
  nlohmann::json cert = smallest_certificate();
  nlohmann::json& m = merge_link(cert);
  // Another colour of the same class, so that only the recovery check can tell.
  std::map<unsigned, std::vector<unsigned>> members;
  for (const auto& c : m["classes"]) members[c[1].get<unsigned>()].push_back(c[0].get<unsigned>());
  bool changed = false;
  for (auto& e : m["recovery"]) {
    const unsigned colour = e[1].get<unsigned>();
    for (const auto& [cls, list] : members)
      if (list.size() > 1 && std::find(list.begin(), list.end(), colour) != list.end()) {
        e[1] = list[0] == colour ? list[1] : list[0];
        changed = true;
        break;
      }
    if (changed) break;
  }
  ASSERT_TRUE(changed);
  const auto r = tilekit::certificate::check(cert, source_tiles());
  EXPECT_FALSE(r.accepted);
  EXPECT_NE(r.error.find("recovery after merge"), std::string::npos) << r.error;
}

TEST(CertificateCheck, RejectsTheRadiusLoweredToOne) {
  nlohmann::json cert = smallest_certificate();
  merge_link(cert)["radius"] = 1;
  auto r = tilekit::certificate::check(cert, source_tiles());
  EXPECT_FALSE(r.accepted);
  EXPECT_NE(r.error.find("radius-1 neighbourhood"), std::string::npos) << r.error;

  // A table of radius 1 made from the radius-2 one (the middle 3x3 pegs, the first colour where two
  // disagree): the composite of the merges is not recovered at radius 1.
  cert = smallest_certificate();
  nlohmann::json& m = merge_link(cert);
  std::map<std::string, unsigned> small;
  for (const auto& e : m["recovery"]) {
    const std::string k = e[0].get<std::string>();
    small.emplace(k.substr(6, 3) + k.substr(11, 3) + k.substr(16, 3), e[1].get<unsigned>());
  }
  nlohmann::json table = nlohmann::json::array();
  for (const auto& [k, c] : small) table.push_back({k, c});
  m["recovery"] = table;
  m["radius"] = 1;
  r = tilekit::certificate::check(cert, source_tiles());
  EXPECT_FALSE(r.accepted);
  EXPECT_NE(r.error.find("recovery after merge"), std::string::npos) << r.error;
}

TEST(CertificateCheck, RejectsAnotherSourceAndAPruneOfANeededTile) {
  nlohmann::json cert = smallest_certificate();
  // Variant 3 differs from variant 2 in one tile: not the published set the certificate names.
  auto r = tilekit::certificate::check(cert, published("jeandel-rao-11-variant-3"));
  EXPECT_FALSE(r.accepted);
  EXPECT_NE(r.error.find("not the published set"), std::string::npos) << r.error;

  for (auto& l : cert["links"])
    if (l["op"] == "translation") {
      // Move a tile of the pruned set into the first prune round.
      l["prune"][0]["removed"].push_back(l["to"]["tiles"][0]);
      l["to"]["tiles"].erase(0);
      break;
    }
  r = tilekit::certificate::check(cert, source_tiles());
  EXPECT_FALSE(r.accepted);
  EXPECT_NE(r.error.find("centre of a 3x3 patch"), std::string::npos) << r.error;
}

TEST(CertificateCheck, RejectsMalformedCertificatesWithoutThrowing) {
  EXPECT_FALSE(tilekit::certificate::check(nlohmann::json::array(), source_tiles()).accepted);
  nlohmann::json cert = smallest_certificate();
  cert["links"][1]["to"]["tiles"][0] = {1, 2, 3};
  const auto r = tilekit::certificate::check(cert, source_tiles());
  EXPECT_FALSE(r.accepted);
  EXPECT_NE(r.error.find("four colours"), std::string::npos) << r.error;
}

}  // namespace
