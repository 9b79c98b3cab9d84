#pragma once
// The real Tiled (Debian's `tiled` 1.8, headless) and a checker of its exported JSON that shares
// nothing with tilemap/: it reads Tiled's own "wangsets" / "wangtiles" / "wangid" arrays and
// a map layer's gids with nlohmann-json, and applies Tiled's matching rule itself (corner sets:
// neighbours share the two corners on their common side; edge sets: the common edge).
#include <array>
#include <cstdlib>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "image/image.hpp"
#include "tests/cli_runner.hpp"

namespace tilekit::test::tiled {

// True when `tiled` and `tmxrasterizer` are on PATH (scripts/setup.sh installs them).
inline bool installed() {
  return std::system("command -v tiled >/dev/null 2>&1 && command -v tmxrasterizer >/dev/null 2>&1") == 0;
}

inline constexpr const char* kSkip = "Tiled is not installed (apt-get install tiled; scripts/setup.sh does)";

// Runs `tiled ARGS` or another Qt tool headless; its exit code.
inline int run_qt(const std::string& program, const std::string& args) {
  const std::string cmd =
      "QT_QPA_PLATFORM=offscreen timeout 120 " + program + " " + args + " >/dev/null 2>&1 </dev/null";
  const int status = std::system(cmd.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128;
}

// The pixels of `theirs` (tmxrasterizer's render) that differ from `ours` (Tilekit's picture of the
// same map); -1 when the sizes differ.
inline int differing_pixels(const Image& theirs, const Image& ours) {
  if (theirs.width != ours.width || theirs.height != ours.height) return -1;
  int differ = 0;
  for (int y = 0; y < ours.height; ++y)
    for (int x = 0; x < ours.width; ++x) differ += theirs.get(x, y) != ours.get(x, y);
  return differ;
}

// One Wang set as Tiled exported it: type and wangid per tile id.
struct WangSetJson {
  std::string type;
  int colours = 0, columns = 0, tilecount = 0;
  std::map<int, std::array<int, 8>> wangid;
};

inline WangSetJson wang_set_of(const nlohmann::json& tileset) {
  WangSetJson w;
  const auto& ws = tileset.at("wangsets").at(0);
  w.type = ws.at("type").get<std::string>();
  w.colours = int(ws.at("colors").size());
  w.columns = tileset.at("columns").get<int>();
  w.tilecount = tileset.at("tilecount").get<int>();
  for (const auto& t : ws.at("wangtiles")) {
    std::array<int, 8> id{};
    for (int k = 0; k < 8; ++k) id[std::size_t(k)] = t.at("wangid").at(std::size_t(k)).get<int>();
    w.wangid[t.at("tileid").get<int>()] = id;
  }
  return w;
}

// Problems of a grid of tile ids (-1: empty) under Tiled's rule: every entry the type uses is a
// colour 1..C, every other 0, and every pair of neighbours agrees (wrapping around with `torus`).
inline std::vector<std::string> mismatches(const WangSetJson& w, const std::vector<int>& ids, int rows, int cols,
                                           bool torus) {
  std::vector<std::string> bad;
  const bool corner = w.type == "corner";
  auto id_at = [&](int r, int c) -> const std::array<int, 8>& {
    const int t = ids[std::size_t(r * cols + c)];
    static const std::array<int, 8> none{};
    auto it = w.wangid.find(t);
    if (it == w.wangid.end()) {
      bad.push_back("tile " + std::to_string(t) + " has no wangid");
      return none;
    }
    return it->second;
  };
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) {
      const auto& a = id_at(r, c);
      for (int k = 0; k < 8; ++k) {
        const bool used = corner ? k % 2 == 1 : k % 2 == 0;
        if (used != (a[std::size_t(k)] >= 1 && a[std::size_t(k)] <= w.colours))
          bad.push_back("cell " + std::to_string(r) + "," + std::to_string(c) + " entry " + std::to_string(k));
      }
      const std::string at = " at " + std::to_string(r) + "," + std::to_string(c);
      if (c + 1 < cols || torus) {
        const auto& b = id_at(r, (c + 1) % cols);
        const bool ok = corner ? a[1] == b[7] && a[3] == b[5] : a[2] == b[6];
        if (!ok) bad.push_back("east neighbour disagrees" + at);
      }
      if (r + 1 < rows || torus) {
        const auto& b = id_at((r + 1) % rows, c);
        const bool ok = corner ? a[5] == b[7] && a[3] == b[1] : a[4] == b[0];
        if (!ok) bad.push_back("south neighbour disagrees" + at);
      }
    }
  return bad;
}

// The sheet of a tileset as a map: tile id r * columns + c at (r, c).
inline std::vector<int> sheet_ids(const WangSetJson& w) {
  std::vector<int> ids(std::size_t(w.tilecount));
  for (int k = 0; k < w.tilecount; ++k) ids[std::size_t(k)] = k;
  return ids;
}

}  // namespace tilekit::test::tiled
