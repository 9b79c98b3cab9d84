// Portfolio statistics files (solver/portfolio_stats.hpp): loading, then everything a run does
// with what loaded (report, ordering candidates, recording, merging).
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <string>

#include "base/error.hpp"
#include "solver/portfolio.hpp"
#include "solver/portfolio_stats.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace tilekit;
  // The loader reads a file; one per process, rewritten for every input.
  static const std::string path = "/tmp/tilekit-fuzz-stats-" + std::to_string(getpid()) + ".json";
  if (std::FILE* f = std::fopen(path.c_str(), "wb")) {
    std::fwrite(data, 1, size, f);
    std::fclose(f);
  }
  try {
    PortfolioStats s = PortfolioStats::load(path);
    s.report().dump();
    s.order(TileKind::Corner, 4, {"t=0,4:pi=1,2,3,0", "t=0,8:pi=1,0,3,2", kPlainSearch});
    PortfolioStats other = s;
    other.record(TileKind::Wang, 2, "t=0,2:pi=1,0", true, 0.5);
    s.merge(other);
    s.report().dump();
  } catch (const InputError&) {
  }
  return 0;
}
