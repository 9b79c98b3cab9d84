// construct_packing(): picks the construction for a kind and colour count, and the matching
// tile -> position map (closed form where one exists, derived from the factors otherwise).
#include "tilesets/constructions.hpp"

#include <fmt/format.h>

#include <nlohmann/json.hpp>
#include <stdexcept>

#include "tilesets/construct_internal.hpp"
#include "tilesets/reference_data.hpp"
#include "tilesets/validator.hpp"

namespace tilekit {

Tiling corner_packing_from_pegs(const std::vector<Colour>& pegs, int n, std::uint32_t colours) {
  Tiling t(TileKind::Corner, colours, n, n, true);
  auto P = [&](int r, int c) { return pegs[std::size_t(r % n) * std::size_t(n) + std::size_t(c % n)]; };
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c) {
      CornerTile ct{P(r, c + 1), P(r + 1, c + 1), P(r + 1, c), P(r, c)};  // ne, se, sw, nw
      t.at(r, c) = corner_index(ct, colours);                             // thesis eq. (2.5)
    }
  return t;
}

std::vector<Colour> pegs_of_corner_packing(const Tiling& t) {
  std::vector<Colour> pegs(t.cells.size());
  for (std::size_t i = 0; i < t.cells.size(); ++i) pegs[i] = corner_tile(t.cells[i], t.colours).nw;
  return pegs;
}

std::optional<Tiling> stored_packing(TileKind kind, std::uint32_t colours) {
  const std::string name = fmt::format("packing-{}-{}.json", kind_name(kind), colours);
  for (const EmbeddedFile& f : reference_data()) {
    if (f.name != name) continue;
    Tiling t = tiling_from_json(nlohmann::json::parse(f.text), name);
    ValidationReport rep = validate(t);
    if (t.kind != kind || t.colours != colours || !rep.packing)
      throw std::logic_error(fmt::format("embedded {} is not a packing of the complete {} set over {} colours", name,
                                         kind_name(kind), colours));
    return t;
  }
  return std::nullopt;
}

namespace {

struct CornerPegs {
  std::vector<Colour> pegs;  // n x n, n = C^2
  std::string how;
  bool closed_form = false;
};

// C = a * b with a the power-of-two part (which must be stored) and b > 1 odd.
std::optional<std::pair<std::uint32_t, std::uint32_t>> product_split(std::uint32_t colours) {
  const std::uint32_t a = colours & (~colours + 1);
  const std::uint32_t b = colours / a;
  if (a < 2 || b < 2) return std::nullopt;
  return std::make_pair(a, b);
}

std::optional<CornerPegs> corner_pegs(std::uint32_t colours) {
  if (colours % 2 == 1) return CornerPegs{corner_triangular_pegs(colours), "debruijn-triangular", true};
  if (auto s = stored_packing(TileKind::Corner, colours)) return CornerPegs{pegs_of_corner_packing(*s), "stored", false};
  auto split = product_split(colours);
  if (!split) return std::nullopt;
  auto [a, b] = *split;
  auto A = corner_pegs(a), B = corner_pegs(b);
  if (!A || !B) return std::nullopt;
  return CornerPegs{corner_product_pegs(A->pegs, a, B->pegs, b),
                    fmt::format("product {}x{} ({} and {})", a, b, A->how, B->how), false};
}

// x = ra (mod ma), x = rb (mod mb), gcd(ma, mb) = 1 (Chinese remainder theorem).
std::int64_t crt(std::int64_t ra, std::int64_t ma, std::int64_t rb, std::int64_t mb) {
  // inverse of ma modulo mb by the extended Euclidean algorithm
  std::int64_t old_r = ma % mb, r = mb, old_s = 1, s = 0;
  while (r != 0) {
    const std::int64_t q = old_r / r;
    std::tie(old_r, r) = std::make_pair(r, old_r - q * r);
    std::tie(old_s, s) = std::make_pair(s, old_s - q * s);
  }
  const std::int64_t inv = ((old_s % mb) + mb) % mb;
  const std::int64_t k = (((rb - ra) % mb + mb) % mb) * inv % mb;
  return ra + ma * k;
}

std::optional<std::pair<int, int>> corner_position(std::uint32_t colours, TileIndex tile) {
  if (colours % 2 == 1) return corner_triangular_position(colours, tile);
  if (auto s = stored_packing(TileKind::Corner, colours)) {
    for (int r = 0; r < s->rows; ++r)
      for (int c = 0; c < s->cols; ++c)
        if (s->at(r, c) == tile) return std::make_pair(r, c);
    return std::nullopt;
  }
  auto split = product_split(colours);
  if (!split) return std::nullopt;
  auto [a, b] = *split;
  // Split every corner colour k = kA + a * kB into the factors' tiles (DESIGN.md product).
  const CornerTile t = corner_tile(tile, colours);
  const CornerTile ta{t.ne % a, t.se % a, t.sw % a, t.nw % a}, tb{t.ne / a, t.se / a, t.sw / a, t.nw / a};
  auto pa = corner_position(a, corner_index(ta, a)), pb = corner_position(b, corner_index(tb, b));
  if (!pa || !pb) return std::nullopt;
  const std::int64_t na = std::int64_t(a) * a, nb = std::int64_t(b) * b;
  return std::make_pair(int(crt(pa->first, na, pb->first, nb)), int(crt(pa->second, na, pb->second, nb)));
}

}  // namespace

std::optional<ConstructedPacking> construct_packing(TileKind kind, std::uint32_t colours) {
  if (colours == 0) return std::nullopt;
  if (kind == TileKind::Wang) return ConstructedPacking{wang_euler_packing(colours), "euler-product", true};
  auto pegs = corner_pegs(colours);
  if (!pegs) return std::nullopt;
  const int n = int(std::uint64_t(colours) * colours);
  return ConstructedPacking{corner_packing_from_pegs(pegs->pegs, n, colours), pegs->how, pegs->closed_form};
}

std::optional<std::pair<int, int>> packing_position(TileKind kind, std::uint32_t colours, TileIndex tile) {
  if (colours == 0 || std::uint64_t(tile) >= complete_size(colours, colours)) return std::nullopt;
  if (kind == TileKind::Wang) return wang_euler_position(colours, tile);
  return corner_position(colours, tile);
}

std::vector<std::uint32_t> constructible_colours(TileKind kind, std::uint32_t max_colours) {
  std::vector<std::uint32_t> out;
  for (std::uint32_t c = 1; c <= max_colours; ++c) {
    bool ok = kind == TileKind::Wang || c % 2 == 1 || stored_packing(kind, c).has_value();
    if (!ok)
      if (auto split = product_split(c)) ok = stored_packing(TileKind::Corner, split->first).has_value();
    if (ok) out.push_back(c);
  }
  return out;
}

}  // namespace tilekit
