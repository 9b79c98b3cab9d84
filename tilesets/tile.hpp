#pragma once
// Wang tiles and corner tiles as small value types, and their index encodings
// (thesis sec. 2.8, eq. 2.1-2.7; mixed radix for C_h != C_v, thesis sec. 2.7).
#include <array>
#include <compare>
#include <cstdint>
#include <string_view>

namespace tilekit {

using Colour = std::uint32_t;
using TileIndex = std::uint32_t;

// Window: the K x L windows of a colouring of the lattice over C symbols (a de Bruijn torus or
// perfect map holds each once; tilesets/window_torus.hpp). Corner tiles are the 2 x 2 case.
enum class TileKind { Wang, Corner, Window };

constexpr std::string_view kind_name(TileKind k) {
  return k == TileKind::Wang ? "wang" : k == TileKind::Corner ? "corner" : "window";
}

// A Wang tile: one colour per edge. N and S edges are horizontal (C_h colours),
// E and W edges are vertical (C_v colours).
struct WangTile {
  Colour n = 0, e = 0, s = 0, w = 0;
  auto operator<=>(const WangTile&) const = default;
};

// A corner tile: one colour per corner.
struct CornerTile {
  Colour ne = 0, se = 0, sw = 0, nw = 0;
  auto operator<=>(const CornerTile&) const = default;
};

// thesis eq. (2.2); mixed radix: N,S in base ch, E,W in base cv (thesis sec. 2.7)
constexpr TileIndex wang_index(const WangTile& t, std::uint32_t ch, std::uint32_t cv) {
  return ((t.n * cv + t.e) * ch + t.s) * cv + t.w;
}
constexpr TileIndex wang_index(const WangTile& t, std::uint32_t c) { return wang_index(t, c, c); }

// thesis eq. (2.3)/(2.4)
constexpr WangTile wang_tile(TileIndex i, std::uint32_t ch, std::uint32_t cv) {
  WangTile t;
  t.w = i % cv;
  i /= cv;
  t.s = i % ch;
  i /= ch;
  t.e = i % cv;
  i /= cv;
  t.n = i;
  return t;
}
constexpr WangTile wang_tile(TileIndex i, std::uint32_t c) { return wang_tile(i, c, c); }

// thesis eq. (2.5)
constexpr TileIndex corner_index(const CornerTile& t, std::uint32_t c) {
  return ((t.ne * c + t.se) * c + t.sw) * c + t.nw;
}

// thesis eq. (2.6)/(2.7)
constexpr CornerTile corner_tile(TileIndex i, std::uint32_t c) {
  CornerTile t;
  t.nw = i % c;
  i /= c;
  t.sw = i % c;
  i /= c;
  t.se = i % c;
  i /= c;
  t.ne = i;
  return t;
}

// Number of tiles of the complete set: C^4 (corner) or (C_h C_v)^2 (Wang, thesis sec. 2.7).
constexpr std::uint64_t complete_size(std::uint64_t ch, std::uint64_t cv) { return ch * ch * cv * cv; }

}  // namespace tilekit
