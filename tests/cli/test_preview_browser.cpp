// `tilekit texture preview` in a real browser: Debian's chromium, headless, WebGL2 on SwiftShader
// (scripts/capture-preview.sh). A capture of the page's ?capture=1 view equals `texture render`
// of the same view within 2/255, for every method, at a seed other than the page's default (so
// the page's own port of the seeded hash tables is exercised) with 16x anisotropic filtering on a
// tilted view; without a method in the query the page opens on tiles. Skipped where chromium is
// missing, unless TILEKIT_REQUIRE_BROWSER=1 (scripts/test.sh sets it after scripts/setup.sh has
// installed chromium): then a missing browser fails the test.
#include <gtest/gtest.h>

#include <cstdlib>

#include "../cli_runner.hpp"
#include "../texture/texture_fixtures.hpp"

namespace tilekit {
namespace {

using test::run_cli;
using test::TempDir;

TEST(PreviewBrowser, ChromiumCaptureOfEveryMethodEqualsTheRenderWithinTwo) {
  if (std::system("command -v chromium >/dev/null 2>&1") != 0) {
    const char* required = std::getenv("TILEKIT_REQUIRE_BROWSER");
    if (required && std::string(required) == "1") FAIL() << "TILEKIT_REQUIRE_BROWSER=1 but chromium is not installed";
    GTEST_SKIP() << "chromium is not installed (scripts/setup.sh installs it)";
  }
  TempDir d;
  write_png(d / "ex.png", test::synthetic_image(96, 96));
  ASSERT_EQ(run_cli("texture tiles --exemplar " + (d / "ex.png") + " --colors 2 --tile-px 16 --search 2 --out " +
                    (d / "t") + " --quiet")
                .code,
            0);
  ASSERT_EQ(run_cli("texture atlas " + (d / "t") + " --out " + (d / "a.png") + " --no-db").code, 0);
  auto page = run_cli("texture preview --atlas " + (d / "a.png") + " --exemplar " + (d / "ex.png") + " --out " +
                      (d / "p.html"));
  ASSERT_EQ(page.code, 0) << page.err;
  const std::string capture = std::string(TILEKIT_SOURCE_DIR) + "/scripts/capture-preview.sh";
  // "": no method in the query, where the page opens on tiles
  for (const std::string method : {"tiles", "hex", "hpn", ""}) {
    const std::string name = method.empty() ? "default" : method;
    const std::string shot = d / (name + "-browser.png"), ref = d / (name + "-render.png");
    ASSERT_EQ(std::system((capture + " " + (d / "p.html") + " 'u=37.5&v=-20&scale=0.7&seed=5&tilt=2.5" +
                           (method.empty() ? "" : "&method=" + method) + "' 200x150 " + shot)
                              .c_str()),
              0)
        << name;
    auto r = run_cli("texture render --method " + (method.empty() ? std::string("tiles") : method) + " --atlas " +
                     (d / "a.png") + " --exemplar " + (d / "ex.png") +
                     " --size 200x150 --origin 37.5,-20 --scale 0.7 --seed 5 --tilt 2.5 --quiet --out " + ref);
    ASSERT_EQ(r.code, 0) << r.err;
    const Image a = read_image(shot), b = read_image(ref);
    ASSERT_EQ(a.width, b.width);
    ASSERT_EQ(a.height, b.height);
    int worst = 0;
    for (int y = 0; y < a.height; ++y)
      for (int x = 0; x < a.width; ++x)
        for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(int(a.at(x, y)[c]) - int(b.at(x, y)[c])));
    EXPECT_LE(worst, 2) << name;
    RecordProperty(name + "_max_difference", worst);
  }
}

}  // namespace
}  // namespace tilekit
