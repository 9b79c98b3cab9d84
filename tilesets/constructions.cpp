// construct_packing(): picks the construction for a kind and colour count, and the matching
// tile -> position map (closed form where one exists, derived from the factors otherwise).
#include "tilesets/constructions.hpp"

#include <fmt/format.h>

#include <cstdio>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "tilesets/construct_internal.hpp"
#include "tilesets/reference_data.hpp"
#include "tilesets/validator.hpp"

namespace tilekit {

namespace {

// The packings of tilesets/data/packing-<kind>-<C>.json, each parsed and checked by the
// independent validator on first use (the embedded data never changes; a C=32 packing takes
// about 0.2 s, so no lookup pays for packings it does not use), with their inverse.
struct StoredPacking {
  Tiling tiling;
  std::vector<std::pair<int, int>> positions;  // tile index -> (row, col)
};

struct StoredSlot {
  const EmbeddedFile* file = nullptr;
  std::once_flag once;
  StoredPacking data;
};

StoredPacking load_stored(const EmbeddedFile& f, TileKind kind, std::uint32_t colours) {
  const std::string name(f.name);
  StoredPacking s{tiling_from_json(nlohmann::json::parse(f.text), name), {}};
  const Tiling& t = s.tiling;
  if (t.kind != kind || t.colours != colours || !validate(t).packing)
    throw std::logic_error(fmt::format("embedded {} is not a packing of the complete set its name says", name));
  s.positions.resize(t.cells.size());
  for (int r = 0; r < t.rows; ++r)
    for (int c = 0; c < t.cols; ++c) s.positions[t.at(r, c)] = {r, c};
  return s;
}

using StoredKey = std::pair<TileKind, std::uint32_t>;

// The embedded packing files by kind and colour count (their names only; nothing is parsed).
std::map<StoredKey, StoredSlot>& stored_slots() {
  using Key = StoredKey;
  static std::map<Key, StoredSlot> slots = [] {
    std::map<Key, StoredSlot> out;
    for (const EmbeddedFile& f : reference_data())
      for (TileKind k : {TileKind::Corner, TileKind::Wang}) {
        const std::string prefix = fmt::format("packing-{}-", kind_name(k));
        if (f.name.rfind(prefix, 0) != 0) continue;
        std::uint32_t c = 0;
        if (std::sscanf(std::string(f.name.substr(prefix.size())).c_str(), "%u.json", &c) == 1)
          out[{k, c}].file = &f;
      }
    return out;
  }();
  return slots;
}

bool has_stored(TileKind kind, std::uint32_t colours) { return stored_slots().count({kind, colours}) != 0; }

const StoredPacking* stored_entry(TileKind kind, std::uint32_t colours) {
  auto& slots = stored_slots();
  auto it = slots.find({kind, colours});
  if (it == slots.end()) return nullptr;
  StoredSlot& slot = it->second;
  std::call_once(slot.once, [&] { slot.data = load_stored(*slot.file, kind, colours); });
  return &slot.data;
}

}  // namespace

std::optional<Tiling> stored_packing(TileKind kind, std::uint32_t colours) {
  if (const StoredPacking* s = stored_entry(kind, colours)) return s->tiling;
  return std::nullopt;
}

namespace {

struct CornerPegs {
  std::vector<Colour> pegs;  // n x n, n = C^2
  std::string how;
  bool closed_form = false;
};

// C = a * b with a the power-of-two part (stored or lifted) and b > 1 odd.
std::optional<std::pair<std::uint32_t, std::uint32_t>> product_split(std::uint32_t colours) {
  const std::uint32_t a = colours & (~colours + 1);
  const std::uint32_t b = colours / a;
  if (a < 2 || b < 2) return std::nullopt;
  return std::make_pair(a, b);
}

// Which construction serves C: odd closed form, stored data, coprime product, binary lift.
bool corner_constructible(std::uint32_t colours) {
  if (colours % 2 == 1 || has_stored(TileKind::Corner, colours)) return true;
  if (auto split = product_split(colours)) return corner_constructible(split->first);
  return colours % 4 == 0 && corner_constructible(colours / 2);
}

std::optional<CornerPegs> corner_pegs(std::uint32_t colours) {
  if (colours % 2 == 1) return CornerPegs{corner_triangular_pegs(colours), "debruijn-triangular", true};
  if (const StoredPacking* s = stored_entry(TileKind::Corner, colours))
    return CornerPegs{pegs_of_corner_torus(s->tiling), "stored", false};
  if (auto split = product_split(colours)) {
    auto [a, b] = *split;
    auto A = corner_pegs(a), B = corner_pegs(b);
    if (!A || !B) return std::nullopt;
    return CornerPegs{corner_product_pegs(A->pegs, a, B->pegs, b),
                      fmt::format("product {}x{} ({} and {})", a, b, A->how, B->how), false};
  }
  if (colours % 4 != 0) return std::nullopt;  // C = 2 has no construction (it is stored)
  const std::uint32_t m = colours / 2;        // C = 2m, m even: the binary lift (construct_lift.cpp)
  auto base = corner_pegs(m);
  if (!base) return std::nullopt;
  const int period = int(m * m), n = 4 * period;
  Tiling lifted = colour_lift(corner_torus_from_pegs(base->pegs, period, period, m),
                              corner_torus_from_pegs(binary_lift_quotient_pegs(std::uint64_t(period)), n, n, 2));
  return CornerPegs{pegs_of_corner_torus(lifted), fmt::format("binary lift 2x{} ({})", m, base->how), false};
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
  if (const StoredPacking* s = stored_entry(TileKind::Corner, colours)) return s->positions[tile];
  auto split = product_split(colours);
  if (!split) {
    if (colours % 4 != 0) return std::nullopt;
    // Binary lift over m = C/2: the digits mod m are the base tile, the digits div m the window
    // of the quotient in the base tile's residue class (construct_lift.cpp).
    const std::uint32_t m = colours / 2;
    const CornerTile t = corner_tile(tile, colours);
    auto pb = corner_position(m, corner_index({t.ne % m, t.se % m, t.sw % m, t.nw % m}, m));
    if (!pb) return std::nullopt;
    return binary_lift_position(std::uint64_t(m) * m, *pb, corner_index({t.ne / m, t.se / m, t.sw / m, t.nw / m}, 2));
  }
  auto [a, b] = *split;
  // Split every corner colour k = kA + a * kB into the factors' tiles (construct_product.cpp).
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
  return ConstructedPacking{corner_torus_from_pegs(pegs->pegs, n, n, colours), pegs->how, pegs->closed_form};
}

std::optional<std::pair<int, int>> packing_position(TileKind kind, std::uint32_t colours, TileIndex tile) {
  if (colours == 0 || std::uint64_t(tile) >= complete_size(colours, colours)) return std::nullopt;
  if (kind == TileKind::Wang) return wang_euler_position(colours, tile);
  return corner_position(colours, tile);
}

std::vector<std::uint32_t> constructible_colours(TileKind kind, std::uint32_t max_colours) {
  std::vector<std::uint32_t> out;
  for (std::uint32_t c = 1; c <= max_colours; ++c)
    if (kind == TileKind::Wang || corner_constructible(c)) out.push_back(c);
  return out;
}

}  // namespace tilekit
