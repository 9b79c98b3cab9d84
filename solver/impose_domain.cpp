#include "solver/impose_domain.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cassert>

#include "base/error.hpp"
#include "solver/problem.hpp"

namespace tilekit {
namespace {

// Position ids: corner pegs r*cols+c; Wang h-edges r*cols+c, v-edges rows*cols + r*cols+c.
struct Grid {
  int rows, cols;
  int pos(int r, int c) const { return ((r % rows + rows) % rows) * cols + ((c % cols + cols) % cols); }
};

// Scan order of the lattice: row-major over the narrowest strip of columns (or column-major over
// the narrowest strip of rows) that meets every translation orbit, then the rest. Sites are
// numbered in this order, so the scanline fallback of the search walks a narrow strip and each
// new site soon completes a cell (t=(0,4) and t=(4,0) then search alike).
std::vector<std::array<int, 2>> scan_order(int rows, int cols, const std::vector<GroupElement>& els) {
  Grid grid{rows, cols};
  auto covers = [&](bool by_cols, int w) {
    std::vector<bool> hit(std::size_t(rows) * std::size_t(cols), false);
    for (int a = 0; a < (by_cols ? rows : cols); ++a)
      for (int b = 0; b < w; ++b) {
        int r = by_cols ? a : b, c = by_cols ? b : a;
        for (const auto& g : els) hit[std::size_t(grid.pos(r + g.dr, c + g.dc))] = true;
      }
    return std::all_of(hit.begin(), hit.end(), [](bool h) { return h; });
  };
  int wc = 1, wr = 1;
  while (wc < cols && !covers(true, wc)) ++wc;
  while (wr < rows && !covers(false, wr)) ++wr;
  bool by_cols = wc * rows <= wr * cols;  // strip area; ties keep row-major
  std::vector<std::array<int, 2>> order;
  std::vector<bool> listed(std::size_t(rows) * std::size_t(cols), false);
  auto push = [&](int r, int c) {
    if (!listed[std::size_t(grid.pos(r, c))]) {
      listed[std::size_t(grid.pos(r, c))] = true;
      order.push_back({r, c});
    }
  };
  if (by_cols) {
    for (int r = 0; r < rows; ++r)
      for (int c = 0; c < wc; ++c) push(r, c);
  } else {
    for (int c = 0; c < cols; ++c)
      for (int r = 0; r < wr; ++r) push(r, c);
  }
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) push(r, c);
  return order;
}

}  // namespace

ImposedGroup build_group(const TilingProblem& problem, const std::string& spec) {
  // A window torus's symbols are permuted like the pegs of a corner torus (the same packing rules:
  // a permutation with a fixed point fixes a constant window).
  const TileKind kind = problem.set.kind() == TileKind::Window ? TileKind::Corner : problem.set.kind();
  return ImposedGroup::build(parse_group_spec(spec), kind, problem.set.horizontal_radix(),
                             problem.set.vertical_radix(), problem.rows, problem.cols, problem.packing);
}

namespace {

// Refuses a group that was not built for the problem's torus, tile kind and colours.
void check_group_fits(const TilingProblem& problem, const ImposedGroup& group) {
  const TileSet& set = problem.set;
  if (!problem.torus)
    throw RequestError("impose", "`impose` needs a torus (translations do not act on a bounded grid)");
  if (problem.rows != group.rows() || problem.cols != group.cols())
    throw RequestError("impose", "`impose`: the group was built for another torus size");
  if (set.kind() != group.kind()) throw RequestError("impose", "`impose`: the group was built for another tile kind");
  if (set.horizontal_radix() != group.ch() || set.vertical_radix() != group.cv())
    throw RequestError("impose", "`impose`: the group was built for another number of colours");
  if (std::max(set.horizontal_radix(), set.vertical_radix()) > 64)
    throw RequestError("impose", "`impose`: at most 64 colours per edge direction");
  if (problem.packing && std::size_t(problem.rows) * std::size_t(problem.cols) != set.size())
    throw InputError(fmt::format("a packing of {} tiles needs a torus of that area, not {}x{}", set.size(),
                                 problem.rows, problem.cols));
}

}  // namespace

FundamentalDomain FundamentalDomain::build(const TilingProblem& problem, const ImposedGroup& group) {
  const TileSet& set = problem.set;
  check_group_fits(problem, group);

  FundamentalDomain m;
  m.kind = set.kind();
  m.ch = set.horizontal_radix();
  m.cv = set.vertical_radix();
  m.rows = problem.rows;
  m.cols = problem.cols;
  m.packing = problem.packing;
  m.group_order = group.order();
  const auto& els = group.elements();
  for (const auto& g : els) {
    for (int cls = 0; cls < 2; ++cls) {
      const auto& p = cls == 0 ? g.ph : g.pv;
      m.perm_tables.emplace_back(p.begin(), p.end());
    }
  }

  // Sites: one representative per orbit of pegs / edges, in scanline order.
  Grid grid{m.rows, m.cols};
  const int area = m.rows * m.cols;
  const bool wang = m.kind == TileKind::Wang;
  m.origin.assign(std::size_t(wang ? 2 * area : area), {-1, -1});
  auto add_site = [&](int r, int c, int cls) {
    int base = cls == 1 ? area : 0;
    if (m.origin[std::size_t(base + grid.pos(r, c))][0] >= 0) return;
    int site = m.num_sites++;
    m.site_colours.push_back(cls == 0 ? m.ch : m.cv);
    for (std::size_t e = 0; e < els.size(); ++e) {
      auto& o = m.origin[std::size_t(base + grid.pos(r + els[e].dr, c + els[e].dc))];
      o = {site, int(e) * 2 + cls};
    }
  };
  for (const auto& [r, c] : scan_order(m.rows, m.cols, els)) {
    add_site(r, c, 0);
    if (wang) add_site(r, c, 1);
  }
  // The scan order lists every position, so every peg / edge has its site and group element.
  assert(std::all_of(m.origin.begin(), m.origin.end(), [&](const auto& o) {
    return o[0] >= 0 && o[0] < m.num_sites && o[1] >= 0 && o[1] < int(m.perm_tables.size());
  }));

  // Representative cells and their slots.
  std::vector<bool> cell_seen(std::size_t(area), false);
  auto slot = [&](int cls, int r, int c, std::uint32_t weight) {
    const auto& o = m.origin[std::size_t((cls == 1 ? area : 0) + grid.pos(r, c))];
    return Slot{o[0], o[1], weight};
  };
  for (int r = 0; r < m.rows; ++r)
    for (int c = 0; c < m.cols; ++c) {
      if (cell_seen[std::size_t(grid.pos(r, c))]) continue;
      for (const auto& g : els) cell_seen[std::size_t(grid.pos(r + g.dr, c + g.dc))] = true;
      std::array<Slot, 4> s;
      if (!wang) {
        std::uint32_t C = m.ch;  // thesis eq. (2.5): ((NE*C + SE)*C + SW)*C + NW
        s = {slot(0, r, c + 1, C * C * C), slot(0, r + 1, c + 1, C * C), slot(0, r + 1, c, C), slot(0, r, c, 1)};
      } else {
        // thesis eq. (2.2), mixed radix: ((N*cv + E)*ch + S)*cv + W
        s = {slot(0, r, c, m.cv * m.ch * m.cv), slot(1, r, c + 1, m.ch * m.cv), slot(0, r + 1, c, m.cv),
             slot(1, r, c, 1)};
      }
      m.cells.push_back(s);
      m.cell_positions.push_back({r, c});
    }

  // The group's elements have distinct translations, so it acts freely on the cells: every cell
  // orbit has |G| cells (what the model's pair counts and the packing's orbit count rely on).
  assert(m.cells.size() * els.size() == std::size_t(area));

  // Tile orbits under G.
  const std::size_t space = std::size_t(complete_size(m.ch, m.cv));
  std::vector<bool> in_set(space, false);
  for (std::size_t k = 0; k < set.size(); ++k) in_set[set.index_of(k)] = true;
  m.orbit_of.assign(space, -2);
  std::vector<TileIndex> orbit;
  for (std::size_t k = 0; k < set.size(); ++k) {
    TileIndex t = set.index_of(k);
    if (m.orbit_of[t] != -2) continue;
    orbit.clear();
    bool usable = true;
    for (std::size_t e = 0; e < els.size(); ++e) {
      TileIndex img = group.apply(els[e], t);
      if (!in_set[img]) {
        if (m.packing)
          throw RequestError("impose", fmt::format("`impose`: the tile set is not closed under the group: tile index "
                                                   "{} maps to {}, which is not in the set",
                                                   t, img));
        usable = false;
      }
      if (e > 0 && img == t) {
        if (m.packing)
          throw RequestError("impose",
                             fmt::format("`impose`: tile index {} is its own image under a non-identity group element; "
                                         "a packing cannot be invariant",
                                         t));
      }
      orbit.push_back(img);
    }
    int id = usable ? m.num_orbits++ : -1;
    for (TileIndex img : orbit) m.orbit_of[img] = id;
  }
  for (auto& o : m.orbit_of)
    if (o == -2) o = -1;
  if (m.packing && std::size_t(m.num_orbits) != m.cells.size())
    throw RequestError("impose", fmt::format("`impose`: {} tile orbits but {} cell orbits; no invariant packing exists",
                                             m.num_orbits, m.cells.size()));
  return m;
}

Tiling FundamentalDomain::to_tiling(const std::vector<int>& values) const {
  assert(values.size() == std::size_t(num_sites));
  for (int s = 0; s < num_sites; ++s)  // every site holds one of its colours
    assert(values[std::size_t(s)] >= 0 && std::uint32_t(values[std::size_t(s)]) < site_colours[std::size_t(s)]);
  Tiling t(kind, ch, rows, cols, true);
  if (kind == TileKind::Wang) t.vertical_colours = cv == ch ? 0 : cv;
  Grid grid{rows, cols};
  const int area = rows * cols;
  auto colour = [&](int cls, int r, int c) -> Colour {
    const auto& o = origin[std::size_t((cls == 1 ? area : 0) + grid.pos(r, c))];
    return perm_tables[std::size_t(o[1])][std::size_t(values[std::size_t(o[0])])];
  };
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) {
      if (kind == TileKind::Corner)
        t.at(r, c) = corner_index(
            CornerTile{colour(0, r, c + 1), colour(0, r + 1, c + 1), colour(0, r + 1, c), colour(0, r, c)}, ch);
      else
        t.at(r, c) =
            wang_index(WangTile{colour(0, r, c), colour(1, r, c + 1), colour(0, r + 1, c), colour(1, r, c)}, ch, cv);
    }
  return t;
}

}  // namespace tilekit
