#include "tiling/tiling_algorithms.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "tiling/direct_tiling.hpp"
#include "base/error.hpp"
#include "tiling/halton_tiling.hpp"
#include "tiling/scanline_tiling.hpp"
#include "tilesets/tile_set_reduction.hpp"

namespace tilekit {

namespace {

struct AlgoName {
  TilingAlgo algo;
  const char* name;
};
constexpr AlgoName kAlgos[] = {{TilingAlgo::Scanline, "scanline"},      {TilingAlgo::Direct, "direct"},
                               {TilingAlgo::DirectEdge, "direct-edge"}, {TilingAlgo::DirectCompact, "direct-compact"},
                               {TilingAlgo::Halton, "halton"},          {TilingAlgo::Controlled, "controlled"}};

void require_kind(const TileSet& set, TileKind kind, TilingAlgo algo) {
  if (set.kind() != kind)
    throw RequestError("algo", fmt::format("`algo` {} makes {} tilings, but tile set '{}' is a {} set",
                                           tiling_algo_name(algo), kind_name(kind), set.name(), kind_name(set.kind())));
}

// Every tile the algorithm can produce must be in the set.
void require_tiles(const TileSet& set, TilingAlgo algo, const std::vector<TileIndex>& producible, const char* hint) {
  std::vector<bool> have(complete_size(set.horizontal_radix(), set.vertical_radix()), false);
  for (std::size_t k = 0; k < set.size(); ++k) have[set.index_of(k)] = true;
  for (TileIndex i : producible)
    if (i >= have.size() || !have[i])
      throw RequestError("algo",
                         fmt::format("`algo` {} can place tiles that tile set '{}' lacks ({} of the {} it can produce "
                                     "are missing); use {}",
                                     tiling_algo_name(algo), set.name(),
                                     std::count_if(producible.begin(), producible.end(),
                                                   [&](TileIndex j) { return j >= have.size() || !have[j]; }),
                                     producible.size(), hint));
}

std::vector<TileIndex> all_indices(std::uint64_t n) {
  std::vector<TileIndex> v(n);
  for (std::uint64_t i = 0; i < n; ++i) v[i] = TileIndex(i);
  return v;
}

}  // namespace

TilingAlgo parse_tiling_algo(const std::string& name) {
  for (const auto& a : kAlgos)
    if (name == a.name) return a.algo;
  throw InputError(
      fmt::format("unknown algorithm '{}' (expected one of: {})", name, fmt::join(tiling_algo_names(), ", ")));
}

const char* tiling_algo_name(TilingAlgo algo) {
  for (const auto& a : kAlgos)
    if (a.algo == algo) return a.name;
  return "?";
}

std::vector<std::string> tiling_algo_names() {
  std::vector<std::string> v;
  for (const auto& a : kAlgos) v.emplace_back(a.name);
  return v;
}

void check_tiling_size(std::int64_t rows, std::int64_t cols) {
  if (rows < 1 || cols < 1 || rows > 65536 || cols > 65536)
    throw InputError(fmt::format("tiling size must be between 1x1 and 65536x65536, got {}x{}", cols, rows));
  if (rows * cols > (std::int64_t(1) << 24))
    throw InputError(fmt::format("tiling of {}x{} tiles is too large (at most 2^24 = 4096x4096 tiles)", cols, rows));
}

Tiling generate_tiling(const TileSet& set, const TilingRequest& req) {
  check_tiling_size(req.rows, req.cols);
  if (set.empty()) throw InputError(fmt::format("tile set '{}' is empty", set.name()));
  const std::uint32_t ch = set.horizontal_radix(), cv = set.vertical_radix();
  const std::uint64_t complete = complete_size(ch, cv);
  switch (req.algo) {
    case TilingAlgo::Scanline:
      return set.kind() == TileKind::Wang ? scanline_wang_tiling(set, req.rows, req.cols, req.seed)
                                          : scanline_corner_tiling(set, req.rows, req.cols, req.seed);
    case TilingAlgo::Direct:
      if (set.kind() == TileKind::Corner) {
        require_tiles(set, req.algo, all_indices(complete), "complete-corner-C");
        return DirectCornerTiling(ch, req.hash, req.seed).generate(req.rows, req.cols);
      }
      require_tiles(set, req.algo, all_indices(complete), "complete-wang-C");
      return DirectWangTiling(ch, cv, req.hash, req.seed).generate(req.rows, req.cols);
    case TilingAlgo::DirectEdge:
      require_kind(set, TileKind::Wang, req.algo);
      require_tiles(set, req.algo, all_indices(complete), "complete-wang-C");
      return DirectEdgeWangTiling(ch, cv, req.hash, req.seed).generate(req.rows, req.cols);
    case TilingAlgo::DirectCompact: {
      require_kind(set, TileKind::Wang, req.algo);
      if (ch != cv)
        throw RequestError("algo",
                           fmt::format("`algo` direct-compact needs one colour count for all edges; tile set '{}' has "
                                       "{} horizontal and {} vertical",
                                       set.name(), ch, cv));
      std::vector<TileIndex> producible;  // thesis sec. 3.3.2.2: N + S = E + W (mod C)
      for (TileIndex i = 0; i < complete; ++i) {
        const WangTile t = wang_tile(i, ch);
        if ((t.n + t.s) % ch == (t.e + t.w) % ch) producible.push_back(i);
      }
      require_tiles(set, req.algo, producible, "compact-wang3-C");
      return DirectCompactWangTiling(ch, req.hash, req.seed).generate(req.rows, req.cols);
    }
    case TilingAlgo::Halton:
      require_kind(set, TileKind::Corner, req.algo);
      require_tiles(set, req.algo, all_indices(complete), "complete-corner-C");
      return HaltonCornerTiling(ch, req.rows, req.cols).generate();
    case TilingAlgo::Controlled: {
      require_kind(set, TileKind::Corner, req.algo);
      const ProbabilityMap map =
          req.map ? *req.map : ProbabilityMap::ramp(ch, 1, std::max(2, std::min(req.cols + 1, int(ch) * 4)));
      if (map.colours != ch)
        throw InputError(
            fmt::format("the probability map has {} colours but tile set '{}' has {}", map.colours, set.name(), ch));
      ControlledColouring colouring(map, req.rows, req.cols, req.hash, req.seed);
      const TileSet reduced = reduced_corner_set(ch, excluded_pairs(ch, colouring.compatible_pairs()));
      std::vector<TileIndex> producible;
      for (std::size_t k = 0; k < reduced.size(); ++k) producible.push_back(reduced.index_of(k));
      require_tiles(set, req.algo, producible, "complete-corner-C or the reduced set of the map");
      return lattice_corner_tiling(colouring, req.rows, req.cols);
    }
  }
  throw InputError("unknown algorithm");
}

}  // namespace tilekit
