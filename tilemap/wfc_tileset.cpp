#include "tilemap/wfc_tileset.hpp"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <functional>
#include <map>
#include <pugixml.hpp>
#include <set>
#include <sstream>

#include "base/error.hpp"
#include "base/input.hpp"

namespace tilekit::tilemap {

namespace {

// The reference's symmetry classes: cardinality, a (rotation by 90 degrees), b (reflection).
struct Symmetry {
  int cardinality;
  std::function<int(int)> a, b;
};

Symmetry symmetry_of(char s, const std::string& where) {
  switch (s) {
    case 'L': return {4, [](int i) { return (i + 1) % 4; }, [](int i) { return i % 2 == 0 ? i + 1 : i - 1; }};
    case 'T': return {4, [](int i) { return (i + 1) % 4; }, [](int i) { return i % 2 == 0 ? i : 4 - i; }};
    case 'I': return {2, [](int i) { return 1 - i; }, [](int i) { return i; }};
    case '\\': return {2, [](int i) { return 1 - i; }, [](int i) { return 1 - i; }};
    case 'F':
      return {8, [](int i) { return i < 4 ? (i + 1) % 4 : 4 + (i - 1) % 4; },
              [](int i) { return i < 4 ? i + 4 : i - 4; }};
    case 'X': return {1, [](int i) { return i; }, [](int i) { return i; }};
    default: throw InputError(fmt::format("{}: symmetry \"{}\" is none of X, I, L, T, \\, F", where, s));
  }
}

Image rotated(const Image& src) {  // the reference's rotate(): result[x + y*n] = src[n-1-y + x*n]
  const int n = src.width;
  Image out(n, n);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x)
      for (int ch = 0; ch < 4; ++ch) out.at(x, y)[ch] = src.at(n - 1 - y, x)[ch];
  return out;
}

Image reflected(const Image& src) {  // the reference's reflect(): result[x + y*n] = src[n-1-x + y*n]
  const int n = src.width;
  Image out(n, n);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x)
      for (int ch = 0; ch < 4; ++ch) out.at(x, y)[ch] = src.at(n - 1 - x, y)[ch];
  return out;
}

std::vector<std::string> words(const std::string& s) {
  std::istringstream in(s);
  std::vector<std::string> out;
  for (std::string w; in >> w;) out.push_back(w);
  return out;
}

}  // namespace

WfcTileset read_wfc_tileset(const std::string& xml_path, const std::string& subset, bool images) {
  const std::string text = read_input_file(xml_path, "WFC tile set", kMaxWfcXmlBytes);
  require_utf8(text, xml_path);
  pugi::xml_document doc;
  const pugi::xml_parse_result parsed = doc.load_buffer(text.data(), text.size(), pugi::parse_default, pugi::encoding_utf8);
  if (!parsed) throw InputError(fmt::format("{}: not XML ({} at byte {})", xml_path, parsed.description(), parsed.offset));
  const pugi::xml_node root = doc.child("set");
  if (!root || !root.child("tiles"))
    throw InputError(fmt::format("{}: not a WFC simple tiled model (no <set><tiles>)", xml_path));
  WfcTileset out;
  out.name = std::filesystem::path(xml_path).stem().string();
  out.subset = subset;
  std::set<std::string> members;
  if (!subset.empty()) {
    bool seen = false;
    for (const pugi::xml_node s : root.child("subsets").children("subset"))
      if (subset == s.attribute("name").value()) {
        seen = true;
        for (const pugi::xml_node t : s.children("tile")) members.insert(t.attribute("name").value());
      }
    if (!seen) throw InputError(fmt::format("{}: no subset \"{}\"", xml_path, subset.substr(0, 64)));
  }
  auto included = [&](const std::string& n) { return subset.empty() || members.count(n) > 0; };
  std::vector<std::array<int, 8>> action;
  std::map<std::string, int> first;
  const std::filesystem::path dir = std::filesystem::path(xml_path).parent_path() / out.name;
  for (const pugi::xml_node tile : root.child("tiles").children("tile")) {
    const std::string name = tile.attribute("name").value();
    const std::string where = fmt::format("{}: tile \"{}\"", xml_path, name.substr(0, 64));
    if (name.empty() || name.find_first_of(" \t\n") != std::string::npos)
      throw InputError(fmt::format("{}: a tile name must be one word", where));
    if (!included(name)) continue;
    if (first.count(name)) throw InputError(fmt::format("{}: listed twice", where));
    const std::string sym = tile.attribute("symmetry").value();
    if (sym.size() > 1) throw InputError(fmt::format("{}: symmetry \"{}\" is not one letter", where, sym.substr(0, 8)));
    const Symmetry s = symmetry_of(sym.empty() ? 'X' : sym[0], where);
    const double weight = tile.attribute("weight").empty() ? 1.0 : tile.attribute("weight").as_double(-1);
    if (!(weight > 0) || !std::isfinite(weight)) throw InputError(fmt::format("{}: weight is not a positive number", where));
    const int T = int(action.size());
    first[name] = T;
    for (int t = 0; t < s.cardinality; ++t) {
      std::array<int, 8> m{t, s.a(t), s.a(s.a(t)), s.a(s.a(s.a(t))), s.b(t), s.b(s.a(t)), s.b(s.a(s.a(t))),
                           s.b(s.a(s.a(s.a(t))))};
      for (int& v : m) v += T;
      action.push_back(m);
      out.names.push_back(fmt::format("{} {}", name, t));
      out.weights.push_back(weight);
    }
    if (images) {
      const Image img = read_image((dir / (name + ".png")).string(), 4);
      if (img.width != img.height || img.width < 1)
        throw InputError(fmt::format("{}: image {}x{} is not square", where, img.width, img.height));
      if (out.tile_px && img.width != out.tile_px)
        throw InputError(fmt::format("{}: image of {} pixels, the others {}", where, img.width, out.tile_px));
      out.tile_px = img.width;
      out.images.push_back(img);
      for (int t = 1; t < s.cardinality; ++t)
        out.images.push_back(t <= 3 ? rotated(out.images[std::size_t(T + t - 1)]) : reflected(out.images[std::size_t(T + t - 4)]));
    }
  }
  const int n = int(action.size());
  if (n == 0) throw InputError(fmt::format("{}: no tiles", xml_path));
  // dense[d][t1][t2], d as the reference: 0 left, 1 down, 2 right, 3 up
  std::vector<char> dense(4 * std::size_t(n) * std::size_t(n), 0);
  auto D = [&](int d, int t1, int t2) -> char& {
    return dense[(std::size_t(d) * std::size_t(n) + std::size_t(t1)) * std::size_t(n) + std::size_t(t2)];
  };
  auto orientation = [&](const std::vector<std::string>& w, const std::string& where) {
    if (w.empty() || w.size() > 2) throw InputError(fmt::format("{}: not \"name\" or \"name k\"", where));
    const auto f = first.find(w[0]);
    if (f == first.end()) throw InputError(fmt::format("{}: unknown tile \"{}\"", where, w[0].substr(0, 64)));
    int k = 0;
    if (w.size() == 2) {
      if (w[1].size() != 1 || w[1][0] < '0' || w[1][0] > '7')
        throw InputError(fmt::format("{}: orientation \"{}\" is not 0-7", where, w[1].substr(0, 8)));
      k = w[1][0] - '0';
    }
    return action[std::size_t(f->second)][std::size_t(k)];
  };
  for (const pugi::xml_node nb : root.child("neighbors").children("neighbor")) {
    const auto left = words(nb.attribute("left").value()), right = words(nb.attribute("right").value());
    if (!left.empty() && !right.empty() && (!included(left[0]) || !included(right[0]))) continue;
    const std::string where = fmt::format("{}: neighbor \"{}\" / \"{}\"", xml_path,
                                          std::string(nb.attribute("left").value()).substr(0, 64),
                                          std::string(nb.attribute("right").value()).substr(0, 64));
    const int L = orientation(left, where), R = orientation(right, where);
    if (L >= n || R >= n) throw InputError(fmt::format("{}: orientation beyond the tile's symmetry", where));
    const int Dn = action[std::size_t(L)][1], U = action[std::size_t(R)][1];
    const auto& aL = action[std::size_t(L)];
    const auto& aR = action[std::size_t(R)];
    const auto& aD = action[std::size_t(Dn)];
    const auto& aU = action[std::size_t(U)];
    D(0, R, L) = 1;
    D(0, aR[6], aL[6]) = 1;
    D(0, aL[4], aR[4]) = 1;
    D(0, aL[2], aR[2]) = 1;
    D(1, U, Dn) = 1;
    D(1, aD[6], aU[6]) = 1;
    D(1, aU[4], aD[4]) = 1;
    D(1, aD[2], aU[2]) = 1;
  }
  for (int t1 = 0; t1 < n; ++t1)
    for (int t2 = 0; t2 < n; ++t2) {
      if (D(0, t1, t2)) D(2, t2, t1) = 1;
      if (D(1, t1, t2)) D(3, t2, t1) = 1;
    }
  static constexpr int ours[4] = {3, 2, 1, 0};  // the reference's left, down, right, up
  for (int d = 0; d < 4; ++d)
    for (int t1 = 0; t1 < n; ++t1)
      for (int t2 = 0; t2 < n; ++t2)
        if (D(d, t1, t2)) out.pairs.push_back({ours[d], t1, t2});
  return out;
}

int wfc_tile_number(const WfcTileset& set, const std::string& name) {
  std::string n = name;
  const auto colon = n.find(':');
  if (colon != std::string::npos) n[colon] = ' ';
  if (n.find(' ') == std::string::npos) n += " 0";
  for (std::size_t t = 0; t < set.names.size(); ++t)
    if (set.names[t] == n) return int(t);
  return -1;
}

}  // namespace tilekit::tilemap
