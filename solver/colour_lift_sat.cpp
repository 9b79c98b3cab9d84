// The lift quotient E (lift_model.hpp) as CNF for cadical: the direct encoding of a CSP.
//   - x(s, v): site s (a peg of E, or a horizontal/vertical edge for Wang tiles) has colour v;
//     one Boolean per site when k = 2, else one per colour with exactly one true.
//   - w(cell, t): the cell shows tile t. The four slot literals that spell t imply w(cell, t);
//     each cell has at most one w, so w(cell, .) is exactly the cell's tile.
//   - Each residue class of cells mod the period holds each k-colour tile exactly once: at most
//     one w(cell, t) over the class (sequential counter, Sinz 2005) and at least one.
//   - Tile 0 sits at cell (0, 0) (translations by multiples of the period, as in the engine).
// For a binary lift over a C=4 packing (C=8) that is 4096 site and 65,536 tile variables.

#include <optional>

#include "solver/colour_lift_model.hpp"
#include "solver/sat_cnf.hpp"
#include "tilesets/constructions.hpp"

namespace tilekit {

namespace {

struct LiftCnf {
  CnfBuilder cnf;
  int n = 0, sites = 0;
  std::uint32_t k = 0;
  TileKind kind = TileKind::Corner;
  int first_site_var = 1;
  int lit(int site, int v) const {  // the literal "site has colour v"
    if (k == 2) return v ? first_site_var + site : -(first_site_var + site);
    return first_site_var + site * int(k) + v;
  }
  // The four sites of cell (r, c) in the tile index's digit order (thesis eq. 2.5 / 2.2).
  std::array<int, 4> cell_sites(int r, int c) const {
    const int r1 = (r + 1) % n, c1 = (c + 1) % n;
    if (kind == TileKind::Corner) return {r * n + c1, r1 * n + c1, r1 * n + c, r * n + c};  // NE, SE, SW, NW pegs
    const int h = 0, v = n * n;  // h(r,c): N edge of cell (r,c); v(r,c): its W edge
    return {h + r * n + c, v + r * n + c1, h + r1 * n + c, v + r * n + c};  // N, E, S, W
  }
};

LiftCnf build_lift_cnf(const LiftProblem& lift) {
  LiftCnf e;
  e.n = lift.quotient.rows;
  e.k = lift.quotient_colours;
  e.kind = lift.quotient.set.kind();
  e.sites = e.kind == TileKind::Corner ? e.n * e.n : 2 * e.n * e.n;
  const int k = int(e.k), n = e.n, P = lift.period;
  e.first_site_var = e.cnf.new_vars(e.k == 2 ? e.sites : e.sites * k);
  if (e.k != 2)
    for (int s = 0; s < e.sites; ++s) {
      std::vector<int> lits;
      for (int v = 0; v < k; ++v) lits.push_back(e.lit(s, v));
      e.cnf.exactly_one(lits);
    }
  const int tiles = k * k * k * k;
  std::vector<std::vector<int>> per_class_tile(std::size_t(P * P * tiles));
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c) {
      const std::array<int, 4> s = e.cell_sites(r, c);
      const int first_w = e.cnf.new_vars(tiles);
      std::vector<int> ws;
      for (int t = 0; t < tiles; ++t) {
        const int d[4] = {t / (k * k * k), t / (k * k) % k, t / k % k, t % k};  // digits, most significant first
        e.cnf.clause({-e.lit(s[0], d[0]), -e.lit(s[1], d[1]), -e.lit(s[2], d[2]), -e.lit(s[3], d[3]), first_w + t});
        ws.push_back(first_w + t);
        per_class_tile[std::size_t(((r % P) * P + c % P) * tiles + t)].push_back(first_w + t);
      }
      e.cnf.at_most_one(ws);
      if (r == 0 && c == 0) e.cnf.clause({first_w});  // tile 0 at (0,0)
    }
  for (const auto& lits : per_class_tile) e.cnf.exactly_one(lits);
  return e;
}

Tiling decode_quotient(const LiftCnf& e, const std::vector<char>& value) {
  auto colour = [&](int site) {
    if (e.k == 2) return Colour(value[std::size_t(e.first_site_var + site)] ? 1 : 0);
    for (int v = 0; v < int(e.k); ++v)
      if (value[std::size_t(e.lit(site, v))]) return Colour(v);
    throw std::logic_error("the SAT model leaves a site without a colour");
  };
  Tiling q(e.kind, e.k, e.n, e.n, true);
  for (int r = 0; r < e.n; ++r)
    for (int c = 0; c < e.n; ++c) {
      const std::array<int, 4> s = e.cell_sites(r, c);
      TileIndex i = 0;
      for (int site : s) i = i * e.k + colour(site);  // the digit order of both tile indices
      q.at(r, c) = i;
    }
  return q;
}

}  // namespace

std::string lift_cnf(const LiftProblem& lift, std::uint64_t* variables, std::uint64_t* clauses) {
  LiftCnf e = build_lift_cnf(lift);
  if (variables) *variables = e.cnf.variables();
  if (clauses) *clauses = e.cnf.clauses();
  return e.cnf.dimacs();
}

SearchResult solve_lift_sat(const LiftProblem& lift, const TilingProblem& problem, const SearchOptions& o,
                            const std::string& fingerprint) {
  std::optional<LiftCnf> e;
  return solve_by_sat(
      problem, o, fingerprint, {"packing", "lift", "tiling", "not a packing"},
      [&]() -> const CnfBuilder& { return (e = build_lift_cnf(lift))->cnf; },
      [&](const std::vector<char>& value) { return colour_lift(lift.base, decode_quotient(*e, value)); });
}

}  // namespace tilekit
