#include "tilesets/validator.hpp"

#include <fmt/format.h>

#include <unordered_set>
#include <vector>

namespace tilekit {

namespace {

// Local decoding, deliberately not shared with the generators (thesis eq. 2.3 / 2.6).
struct Digits {
  std::uint32_t d[4];  // most significant first: N E S W (Wang) or NE SE SW NW (corner)
};

Digits decode(TileIndex i, std::uint64_t ch, std::uint64_t cv, bool wang) {
  Digits x{};
  std::uint64_t v = i;
  x.d[3] = std::uint32_t(v % (wang ? cv : ch));
  v /= (wang ? cv : ch);
  x.d[2] = std::uint32_t(v % ch);
  v /= ch;
  x.d[1] = std::uint32_t(v % (wang ? cv : ch));
  v /= (wang ? cv : ch);
  x.d[0] = std::uint32_t(v);
  return x;
}

// A set of tile indices below `n`: a flag per index when that is small (a C=32 corner packing
// has a million cells; hashing them took seconds), a hash set otherwise.
class IndexSet {
 public:
  explicit IndexSet(std::uint64_t n) : dense_(n <= (std::uint64_t(1) << 24)) {
    if (dense_) flags_.assign(std::size_t(n), 0);
  }
  bool insert(TileIndex i) {  // true when new
    if (!dense_) return sparse_.insert(i).second;
    if (flags_[i]) return false;
    flags_[i] = 1;
    return true;
  }
  bool contains(TileIndex i) const { return dense_ ? flags_[i] != 0 : sparse_.count(i) != 0; }

 private:
  bool dense_;
  std::vector<char> flags_;
  std::unordered_set<TileIndex> sparse_;
};

// Window tori (tilesets/window_torus.hpp), decoded here on their own: each cell's index gives
// its K x L symbols (row by row, the first most significant); neighbouring windows must agree
// where they overlap (the right one shifted by a column, the lower one by a row), which on a
// torus is exactly "the windows of one colouring"; a packing holds every window once.
ValidationReport validate_windows(const Tiling& t, const TileSet* set, std::size_t max_errors) {
  ValidationReport rep;
  std::size_t error_count = 0;
  auto error = [&](std::string msg) {
    if (rep.errors.size() < max_errors) rep.errors.push_back(std::move(msg));
    ++error_count;
  };
  const int K = t.window_rows, L = t.window_cols;
  const std::uint64_t C = t.colours;
  std::uint64_t windows = 1;
  for (int d = 0; d < K * L && windows <= (std::uint64_t(1) << 32); ++d) windows *= C;
  if (K < 1 || L < 1 || C < 1 || windows > (std::uint64_t(1) << 32)) {
    rep.errors.push_back(fmt::format("a {}x{} window over {} symbols has no 32-bit index", K, L, C));
    return rep;
  }
  if (t.rows < 1 || t.cols < 1 || t.cells.size() != std::size_t(t.rows) * std::size_t(t.cols)) {
    rep.errors.push_back(fmt::format("grid has {} cells, expected {}x{}", t.cells.size(), t.rows, t.cols));
    return rep;
  }
  if (set && (set->kind() != TileKind::Window || set->window_rows() != K || set->window_cols() != L ||
              set->horizontal_radix() != C))
    error(fmt::format("the tiling's {}x{} windows over {} symbols are not those of tile set '{}'", K, L, C,
                      set->name()));
  const std::size_t per = std::size_t(K) * std::size_t(L);
  std::vector<std::uint32_t> digits(t.cells.size() * per);
  for (std::size_t i = 0; i < t.cells.size(); ++i) {
    std::uint64_t v = t.cells[i];
    if (v >= windows) {
      error(fmt::format("cell ({},{}): window index {} is out of range (< {})", i / std::size_t(t.cols),
                        i % std::size_t(t.cols), v, windows));
      continue;
    }
    for (std::size_t d = per; d-- > 0; v /= C) digits[i * per + d] = std::uint32_t(v % C);
  }
  auto sym = [&](int r, int c, int a, int b) {
    return digits[(std::size_t(r) * std::size_t(t.cols) + std::size_t(c)) * per + std::size_t(a) * std::size_t(L) +
                  std::size_t(b)];
  };
  if (error_count == 0)
    for (int r = 0; r < t.rows; ++r)
      for (int c = 0; c < t.cols; ++c) {
        if (c + 1 < t.cols || t.torus) {
          const int c1 = (c + 1) % t.cols;
          bool ok = true;
          for (int a = 0; a < K; ++a)
            for (int b = 0; b + 1 < L; ++b) ok = ok && sym(r, c, a, b + 1) == sym(r, c1, a, b);
          if (!ok) error(fmt::format("the windows at ({},{}) and ({},{}) do not overlap consistently", r, c, r, c1));
        }
        if (r + 1 < t.rows || t.torus) {
          const int r1 = (r + 1) % t.rows;
          bool ok = true;
          for (int a = 0; a + 1 < K; ++a)
            for (int b = 0; b < L; ++b) ok = ok && sym(r, c, a + 1, b) == sym(r1, c, a, b);
          if (!ok) error(fmt::format("the windows at ({},{}) and ({},{}) do not overlap consistently", r, c, r1, c));
        }
      }
  rep.valid = error_count == 0;
  if (rep.valid && t.torus) {
    IndexSet seen(windows);
    std::size_t distinct = 0;
    for (TileIndex i : t.cells) distinct += seen.insert(i);
    rep.packing = t.cells.size() == windows && distinct == windows;
  }
  if (error_count > rep.errors.size())
    rep.errors.push_back(fmt::format("... and {} more errors", error_count - rep.errors.size()));
  return rep;
}

}  // namespace

ValidationReport validate(const Tiling& t, const TileSet* set, std::size_t max_errors) {
  if (t.kind == TileKind::Window) return validate_windows(t, set, max_errors);
  ValidationReport rep;
  std::size_t error_count = 0;
  auto error = [&](std::string msg) {
    if (rep.errors.size() < max_errors) rep.errors.push_back(std::move(msg));
    ++error_count;
  };
  const bool wang = t.kind == TileKind::Wang;
  const std::uint64_t ch = t.ch(), cv = wang ? t.cv() : t.ch();
  const std::uint64_t ntiles = ch * ch * cv * cv;
  if (t.rows < 1 || t.cols < 1) {
    rep.errors.push_back("the grid is empty");
    return rep;
  }
  if (t.cells.size() != std::size_t(t.rows) * std::size_t(t.cols)) {
    rep.errors.push_back(fmt::format("grid has {} cells, expected {}x{}", t.cells.size(), t.rows, t.cols));
    return rep;
  }
  if (set && set->kind() == TileKind::Window) {
    rep.errors.push_back(fmt::format("a {} tiling is not made of the windows of '{}'", kind_name(t.kind), set->name()));
    return rep;
  }
  if (set) {
    if (set->kind() != t.kind)
      error(fmt::format("tiling is {} but tile set '{}' is {}", kind_name(t.kind), set->name(), kind_name(set->kind())));
    if (set->horizontal_radix() > ch || set->vertical_radix() > cv)
      error(fmt::format("tile set '{}' uses more colours than the tiling's {}", set->name(), ch));
  }
  IndexSet members(set ? ntiles : 0);
  if (set && error_count == 0)
    for (std::size_t k = 0; k < set->size(); ++k) {
      // re-encode the set's tiles under the tiling's radix
      std::vector<Colour> f = set->file_colours(k);
      TileIndex idx = wang ? TileIndex(((f[0] * cv + f[3]) * ch + f[1]) * cv + f[2])   // n e s w
                           : TileIndex(((f[1] * ch + f[3]) * ch + f[2]) * ch + f[0]);  // ne se sw nw
      members.insert(idx);
    }
  std::vector<Digits> dig(t.cells.size());
  for (int r = 0; r < t.rows; ++r)
    for (int c = 0; c < t.cols; ++c) {
      TileIndex i = t.at(r, c);
      if (i >= ntiles) {
        error(fmt::format("cell ({},{}): tile index {} is out of range (< {})", r, c, i, ntiles));
        continue;
      }
      if (set && error_count == 0 && !members.contains(i))
        error(fmt::format("cell ({},{}): tile {} is not in tile set '{}'", r, c, i, set->name()));
      dig[std::size_t(r) * t.cols + c] = decode(i, ch, cv, wang);
    }
  if (error_count == 0) {
    auto cell = [&](int r, int c) -> const Digits& { return dig[std::size_t(r) * t.cols + c]; };
    for (int r = 0; r < t.rows; ++r)
      for (int c = 0; c < t.cols; ++c) {
        const Digits& a = cell(r, c);
        if (c + 1 < t.cols || t.torus) {
          const Digits& b = cell(r, (c + 1) % t.cols);
          // Wang: E(a) == W(b). Corner: NE(a) == NW(b), SE(a) == SW(b).
          bool ok = wang ? a.d[1] == b.d[3] : (a.d[0] == b.d[3] && a.d[1] == b.d[2]);
          if (!ok) error(fmt::format("cells ({},{}) and ({},{}) do not match horizontally", r, c, r, (c + 1) % t.cols));
        }
        if (r + 1 < t.rows || t.torus) {
          const Digits& b = cell((r + 1) % t.rows, c);
          // Wang: S(a) == N(b). Corner: SW(a) == NW(b), SE(a) == NE(b).
          bool ok = wang ? a.d[2] == b.d[0] : (a.d[2] == b.d[3] && a.d[1] == b.d[0]);
          if (!ok) error(fmt::format("cells ({},{}) and ({},{}) do not match vertically", r, c, (r + 1) % t.rows, c));
        }
      }
  }
  rep.valid = error_count == 0;
  if (rep.valid && t.torus) {
    const std::size_t expected = set ? set->size() : std::size_t(ntiles);
    IndexSet seen(ntiles);
    std::size_t distinct = 0;
    for (TileIndex i : t.cells) distinct += seen.insert(i);
    rep.packing = t.cells.size() == expected && distinct == expected;
  }
  if (error_count > rep.errors.size())
    rep.errors.push_back(fmt::format("... and {} more errors", error_count - rep.errors.size()));
  return rep;
}

}  // namespace tilekit
