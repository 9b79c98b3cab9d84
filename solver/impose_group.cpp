#include "solver/impose_group.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cassert>
#include <map>
#include <numeric>
#include <utility>

#include "base/error.hpp"

namespace tilekit {
namespace {

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

std::vector<std::string_view> split(std::string_view s, char sep) {
  std::vector<std::string_view> out;
  std::size_t start = 0;
  for (std::size_t i = 0; i <= s.size(); ++i) {
    if (i == s.size() || s[i] == sep) {
      out.push_back(s.substr(start, i - start));
      start = i + 1;
    }
  }
  return out;
}

long parse_int(std::string_view s, const std::string& where) {
  s = trim(s);
  if (s.empty()) throw RequestError("impose", fmt::format("`impose`: {}: expected a number", where));
  bool neg = false;
  if (s.front() == '-' || s.front() == '+') {
    neg = s.front() == '-';
    s.remove_prefix(1);
  }
  if (s.empty() || s.size() > 9) throw RequestError("impose", fmt::format("`impose`: {}: bad number", where));
  long v = 0;
  for (char ch : s) {
    if (ch < '0' || ch > '9') throw RequestError("impose", fmt::format("`impose`: {}: '{}' is not a number", where, s));
    v = v * 10 + (ch - '0');
  }
  return neg ? -v : v;
}

// Numbers separated by commas and/or spaces.
std::vector<Colour> parse_numbers(std::string_view s, const std::string& where) {
  std::vector<Colour> out;
  std::string token;
  auto flush = [&] {
    if (token.empty()) return;
    long v = parse_int(token, where);
    if (v < 0) throw RequestError("impose", fmt::format("`impose`: {}: colours are not negative", where));
    out.push_back(Colour(v));
    token.clear();
  };
  for (char ch : s) {
    if (ch == ',' || ch == ' ')
      flush();
    else
      token.push_back(ch);
  }
  flush();
  return out;
}

PermutationSpec parse_permutation(std::string_view s, const std::string& where) {
  PermutationSpec p;
  p.given = true;
  s = trim(s);
  if (s.empty()) throw RequestError("impose", fmt::format("`impose`: {}: empty permutation", where));
  if (s.front() == '(') {
    p.cycles = true;
    while (!s.empty()) {
      if (s.front() != '(')
        throw RequestError("impose", fmt::format("`impose`: {}: expected '(' in cycle notation", where));
      auto close = s.find(')');
      if (close == std::string_view::npos)
        throw RequestError("impose", fmt::format("`impose`: {}: missing ')'", where));
      p.parts.push_back(parse_numbers(s.substr(1, close - 1), where));
      if (p.parts.back().empty()) throw RequestError("impose", fmt::format("`impose`: {}: empty cycle", where));
      s = trim(s.substr(close + 1));
    }
  } else {
    p.parts.push_back(parse_numbers(s, where));
  }
  return p;
}

std::string format_perm(const std::vector<Colour>& p) {
  return fmt::format("{}", fmt::join(p, ","));
}

bool is_identity(const std::vector<Colour>& p) {
  for (std::size_t i = 0; i < p.size(); ++i)
    if (p[i] != i) return false;
  return true;
}

std::vector<Colour> compose(const std::vector<Colour>& second, const std::vector<Colour>& first) {
  std::vector<Colour> r(first.size());
  for (std::size_t i = 0; i < first.size(); ++i) r[i] = second[first[i]];
  return r;
}

int fixed_point(const std::vector<Colour>& p) {
  for (std::size_t i = 0; i < p.size(); ++i)
    if (p[i] == i) return int(i);
  return -1;
}

int mod(long a, int n) {
  return int(((a % n) + n) % n);
}

}  // namespace

std::vector<Colour> PermutationSpec::resolve(std::uint32_t n, const std::string& what) const {
  std::vector<Colour> p(n);
  std::iota(p.begin(), p.end(), Colour(0));
  if (!given) return p;
  if (!cycles) {
    const auto& list = parts.at(0);
    if (list.size() != n)
      throw RequestError("impose",
                         fmt::format("`impose`: {} has {} entries but there are {} colours", what, list.size(), n));
    std::vector<bool> seen(n, false);
    for (Colour c : list) {
      if (c >= n)
        throw RequestError("impose",
                           fmt::format("`impose`: {} maps to colour {}, but colours are 0..{}", what, c, n - 1));
      if (seen[c])
        throw RequestError("impose", fmt::format("`impose`: {} is not a permutation (colour {} twice)", what, c));
      seen[c] = true;
    }
    return list;
  }
  std::vector<bool> seen(n, false);
  for (const auto& cyc : parts) {
    for (std::size_t i = 0; i < cyc.size(); ++i) {
      Colour a = cyc[i], b = cyc[(i + 1) % cyc.size()];
      if (a >= n)
        throw RequestError("impose",
                           fmt::format("`impose`: {} names colour {}, but colours are 0..{}", what, a, n - 1));
      if (seen[a]) throw RequestError("impose", fmt::format("`impose`: {}: colour {} is in two cycles", what, a));
      seen[a] = true;
      p[a] = b;
    }
  }
  return p;
}

GroupSpec parse_group_spec(std::string_view text) {
  GroupSpec spec;
  if (trim(text).empty()) throw RequestError("impose", "`impose`: empty group spec (expected e.g. t=0,4:pi=1,2,3,0)");
  int k = 0;
  for (auto gen_text : split(text, ';')) {
    ++k;
    std::string where = fmt::format("generator {} '{}'", k, trim(gen_text));
    GroupGenerator g;
    bool have_t = false;
    for (auto field : split(gen_text, ':')) {
      field = trim(field);
      auto eq = field.find('=');
      if (eq == std::string_view::npos)
        throw RequestError(
            "impose", fmt::format("`impose`: {}: field '{}' is not key=value (keys: t, pi, pih, piv)", where, field));
      auto key = trim(field.substr(0, eq));
      auto value = field.substr(eq + 1);
      if (key == "t") {
        auto parts = split(value, ',');
        if (parts.size() != 2)
          throw RequestError("impose", fmt::format("`impose`: {}: t needs two numbers, rows,cols", where));
        g.dr = int(parse_int(parts[0], where));
        g.dc = int(parse_int(parts[1], where));
        have_t = true;
      } else if (key == "pi" || key == "pih" || key == "piv") {
        PermutationSpec& p = key == "pi" ? g.pi : key == "pih" ? g.pih : g.piv;
        if (p.given) throw RequestError("impose", fmt::format("`impose`: {}: {} given twice", where, key));
        p = parse_permutation(value, where);
      } else {
        throw RequestError("impose", fmt::format("`impose`: {}: unknown key '{}' (keys: t, pi, pih, piv)", where, key));
      }
    }
    if (!have_t) throw RequestError("impose", fmt::format("`impose`: {}: missing the translation t=DR,DC", where));
    if (g.pi.given && (g.pih.given || g.piv.given))
      throw RequestError("impose", fmt::format("`impose`: {}: give either pi or pih/piv, not both", where));
    spec.generators.push_back(std::move(g));
  }
  return spec;
}

std::uint64_t permutation_order(const std::vector<Colour>& p) {
  std::uint64_t order = 1;
  std::vector<bool> seen(p.size(), false);
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (seen[i]) continue;
    std::uint64_t len = 0;
    for (std::size_t j = i; !seen[j]; j = p[j]) {
      seen[j] = true;
      ++len;
    }
    order = std::lcm(order, len);
  }
  return order;
}

std::uint64_t translation_order(int dr, int dc, int rows, int cols) {
  auto one = [](int d, int n) -> std::uint64_t {
    d = mod(d, n);
    return std::uint64_t(n / std::gcd(d, n));  // gcd(0, n) = n -> order 1
  };
  return std::lcm(one(dr, rows), one(dc, cols));
}

ImposedGroup ImposedGroup::build(const GroupSpec& spec, TileKind kind, std::uint32_t ch, std::uint32_t cv, int rows,
                                 int cols, bool packing) {
  if (rows <= 0 || cols <= 0) throw RequestError("impose", "`impose` needs a torus with positive size");
  if (spec.generators.empty()) throw RequestError("impose", "`impose`: no generators");
  if (kind == TileKind::Corner) cv = ch;
  ImposedGroup G;
  G.kind_ = kind;
  G.ch_ = ch;
  G.cv_ = cv;
  G.rows_ = rows;
  G.cols_ = cols;
  int k = 0;
  for (const auto& gs : spec.generators) {
    ++k;
    GroupElement g;
    g.dr = mod(gs.dr, rows);
    g.dc = mod(gs.dc, cols);
    std::string where = fmt::format("generator {} (t={},{})", k, gs.dr, gs.dc);
    if (kind == TileKind::Corner) {
      if (gs.pih.given || gs.piv.given)
        throw RequestError("impose",
                           fmt::format("`impose`: {}: pih/piv are for Wang tiles; corner tiles take pi", where));
      g.ph = gs.pi.resolve(ch, where + " pi");
      g.pv = g.ph;
    } else if (gs.pi.given) {
      if (ch != cv)
        throw RequestError(
            "impose",
            fmt::format("`impose`: {}: the edge directions have different colour counts; use pih/piv", where));
      g.ph = gs.pi.resolve(ch, where + " pi");
      g.pv = g.ph;
    } else {
      g.ph = gs.pih.resolve(ch, where + " pih");
      g.pv = gs.piv.resolve(cv, where + " piv");
    }
    std::uint64_t tord = translation_order(g.dr, g.dc, rows, cols);
    std::uint64_t pord = std::lcm(permutation_order(g.ph), permutation_order(g.pv));
    if (packing && tord != pord)
      throw RequestError(
          "impose",
          fmt::format(
              "`impose`: {}: the translation has order {} on the {}x{} torus but the colour permutation has order {}; "
              "a packing needs them equal",
              where, tord, rows, cols, pord));
    if (!packing && tord % pord != 0)
      throw RequestError(
          "impose",
          fmt::format(
              "`impose`: {}: the permutation's order {} does not divide the translation's order {} on the {}x{} torus",
              where, pord, tord, rows, cols));
    G.generators_.push_back(std::move(g));
  }
  // Close under composition: (t1, p1) then (t2, p2) is (t1 + t2, p2 o p1).
  GroupElement id;
  id.ph.resize(ch);
  id.pv.resize(cv);
  std::iota(id.ph.begin(), id.ph.end(), Colour(0));
  std::iota(id.pv.begin(), id.pv.end(), Colour(0));
  std::map<std::pair<int, int>, std::size_t> by_translation;
  G.elements_.push_back(id);
  by_translation[{0, 0}] = 0;
  for (std::size_t i = 0; i < G.elements_.size(); ++i) {
    for (const auto& gen : G.generators_) {
      GroupElement e = G.elements_[i];
      e.dr = (e.dr + gen.dr) % rows;
      e.dc = (e.dc + gen.dc) % cols;
      e.ph = compose(gen.ph, e.ph);
      e.pv = compose(gen.pv, e.pv);
      auto it = by_translation.find({e.dr, e.dc});
      if (it != by_translation.end()) {
        const auto& old = G.elements_[it->second];
        if (old.ph != e.ph || old.pv != e.pv)
          throw RequestError(
              "impose",
              fmt::format(
                  "`impose`: the generators are inconsistent: translation ({},{}) is reached with two different colour "
                  "permutations ({} and {})",
                  e.dr, e.dc, format_perm(old.ph), format_perm(e.ph)));
        continue;
      }
      by_translation[{e.dr, e.dc}] = G.elements_.size();
      G.elements_.push_back(std::move(e));
    }
  }
  // Identity first; the elements are distinct translations of the rows x cols torus, so their
  // number (the group order) divides its area (Lagrange).
  assert(G.elements_.front().dr == 0 && G.elements_.front().dc == 0 && is_identity(G.elements_.front().ph));
  assert((std::uint64_t(rows) * std::uint64_t(cols)) % G.elements_.size() == 0);
  if (packing) {
    // A tile fixed by a non-identity element would appear at x and at x + t: twice.
    for (std::size_t i = 1; i < G.elements_.size(); ++i) {
      const auto& e = G.elements_[i];
      int fh = fixed_point(e.ph), fv = fixed_point(e.pv);
      if (fh < 0 || fv < 0) continue;
      std::string what = i <= G.generators_.size() && G.generators_[i - 1].dr == e.dr && G.generators_[i - 1].dc == e.dc
                             ? "generator"
                             : "group element";
      if (kind == TileKind::Corner)
        throw RequestError(
            "impose",
            fmt::format("`impose`: {} t={},{}:pi={} fixes colour {}, so the tile with all corners {} is its own image; "
                        "a packing needs permutations without fixed points",
                        what, e.dr, e.dc, format_perm(e.ph), fh, fh));
      throw RequestError(
          "impose",
          fmt::format(
              "`impose`: {} t={},{}:pih={}:piv={} fixes horizontal colour {} and vertical colour {}, so the tile "
              "N={} E={} S={} W={} is its own image; a packing needs pih or piv without a fixed point",
              what, e.dr, e.dc, format_perm(e.ph), format_perm(e.pv), fh, fv, fh, fv, fh, fv));
    }
  }
  return G;
}

TileIndex ImposedGroup::apply(const GroupElement& g, TileIndex tile) const {
  if (kind_ == TileKind::Corner) {
    CornerTile t = corner_tile(tile, ch_);
    return corner_index(CornerTile{g.ph[t.ne], g.ph[t.se], g.ph[t.sw], g.ph[t.nw]}, ch_);
  }
  WangTile t = wang_tile(tile, ch_, cv_);
  return wang_index(WangTile{g.ph[t.n], g.pv[t.e], g.ph[t.s], g.pv[t.w]}, ch_, cv_);
}

Tiling ImposedGroup::apply(const GroupElement& g, const Tiling& t) const {
  Tiling out = t;
  for (int r = 0; r < t.rows; ++r)
    for (int c = 0; c < t.cols; ++c) out.at((r + g.dr) % t.rows, (c + g.dc) % t.cols) = apply(g, t.at(r, c));
  return out;
}

bool ImposedGroup::is_invariant(const Tiling& t) const {
  if (t.rows != rows_ || t.cols != cols_ || t.kind != kind_ || t.ch() != ch_) return false;
  for (const auto& g : generators_)
    if (apply(g, t).cells != t.cells) return false;
  return true;
}

std::string ImposedGroup::spec_text() const {
  std::vector<std::string> gens;
  for (const auto& g : generators_) {
    if (kind_ == TileKind::Corner || g.ph == g.pv)
      gens.push_back(fmt::format("t={},{}:pi={}", g.dr, g.dc, format_perm(g.ph)));
    else if (is_identity(g.pv))
      gens.push_back(fmt::format("t={},{}:pih={}", g.dr, g.dc, format_perm(g.ph)));
    else if (is_identity(g.ph))
      gens.push_back(fmt::format("t={},{}:piv={}", g.dr, g.dc, format_perm(g.pv)));
    else
      gens.push_back(fmt::format("t={},{}:pih={}:piv={}", g.dr, g.dc, format_perm(g.ph), format_perm(g.pv)));
  }
  return fmt::format("{}", fmt::join(gens, ";"));
}

nlohmann::json ImposedGroup::to_json() const {
  nlohmann::json gens = nlohmann::json::array();
  for (const auto& g : generators_) {
    nlohmann::json j = {{"t", {g.dr, g.dc}}};
    if (kind_ == TileKind::Corner || g.ph == g.pv)
      j["pi"] = g.ph;
    else {
      j["pih"] = g.ph;
      j["piv"] = g.pv;
    }
    gens.push_back(std::move(j));
  }
  return {{"spec", spec_text()}, {"order", order()}, {"generators", std::move(gens)}};
}

}  // namespace tilekit
