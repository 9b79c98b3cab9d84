// End-to-end tests of `tilekit aperiodic certify` and `aperiodic check-certificate`: the exit codes
// (0 accepted, 1 rejected with the failed check named, 2 for a file that is no certificate) and,
// labelled slow, that certify writes the checked-in certificate again byte for byte.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "tests/build_paths.hpp"
#include "tests/cli_runner.hpp"

namespace {

std::string checked_in(const std::string& name) {
  std::ifstream in(std::string(TILEKIT_SOURCE_DIR) + "/certificate/data/" + name);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(CertificateCli, RejectionIsExit1AndNamesTheCheckGarbageIsExit2) {
  tilekit::test::TempDir d;
  nlohmann::json cert = nlohmann::json::parse(checked_in("smallest-25.json"));
  for (auto& l : cert["links"])
    if (l["op"] == "merge") l["radius"] = 1;
  tilekit::test::write_text(d / "r1.json", cert.dump());
  auto r = tilekit::test::run_cli("aperiodic check-certificate " + d / "r1.json" + " --json");
  EXPECT_EQ(r.code, 1) << r.err;
  const auto j = r.json();
  EXPECT_EQ(j["accepted"], false);
  EXPECT_NE(j["error"].get<std::string>().find("radius-1 neighbourhood"), std::string::npos);

  tilekit::test::write_text(d / "junk.json", "{not json");
  r = tilekit::test::run_cli("aperiodic check-certificate " + d / "junk.json");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("junk.json"), std::string::npos) << r.err;

  cert["source"]["name"] = "no-such-set";
  tilekit::test::write_text(d / "src.json", cert.dump());
  r = tilekit::test::run_cli("aperiodic check-certificate " + d / "src.json");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("not a published set"), std::string::npos) << r.err;

  r = tilekit::test::run_cli("aperiodic certify --out " + d / "x.json" + " " + d / "junk.json");
  EXPECT_EQ(r.code, 2) << r.err;
}

// About a minute: the chain re-derived, every table rebuilt, then checked.
TEST(CertificateCli, CertifyWritesTheCheckedInCertificateAgain) {
  tilekit::test::TempDir d;
  auto r = tilekit::test::run_cli("aperiodic certify --out " + d / "c.json" + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.json()["accepted"], true);
  EXPECT_EQ(r.json()["result_tiles"], 25);
  std::ifstream in(d / "c.json");
  std::stringstream s;
  s << in.rdbuf();
  EXPECT_EQ(s.str(), checked_in("smallest-25.json"));
}

}  // namespace
