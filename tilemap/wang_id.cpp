#include "tilemap/wang_id.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <charconv>

#include "base/error.hpp"

namespace tilekit::tilemap {

std::string_view wang_type_name(TileKind kind) {
  if (kind == TileKind::Corner) return "corner";
  if (kind == TileKind::Wang) return "edge";
  throw InputError("Tiled Wang sets hold corner or Wang (edge) tiles, not windows");
}

WangId wang_id_of(const WangTile& t) {
  return {t.n + 1, 0, t.e + 1, 0, t.s + 1, 0, t.w + 1, 0};
}

WangId wang_id_of(const CornerTile& t) {
  return {0, t.ne + 1, 0, t.se + 1, 0, t.sw + 1, 0, t.nw + 1};
}

WangId wang_id_of(TileKind kind, std::uint32_t colours, TileIndex index) {
  return kind == TileKind::Wang ? wang_id_of(wang_tile(index, colours)) : wang_id_of(corner_tile(index, colours));
}

namespace {

constexpr std::string_view kSlotNames[8] = {"top",    "top-right",   "right", "bottom-right",
                                            "bottom", "bottom-left", "left",  "top-left"};

// Colour (from 0) of slot `s`, which the kind needs; the slots it does not use must be unset.
Colour needed(const WangId& id, int s, std::uint32_t colours, const std::string& where) {
  if (id[std::size_t(s)] == 0)
    throw InputError(fmt::format("{}: the {} entry of wangid {} is unset (0); Tilekit needs every {} set", where,
                                 kSlotNames[s], format_wang_id(id), s % 2 ? "corner" : "edge"));
  if (id[std::size_t(s)] > colours)
    throw InputError(fmt::format("{}: the {} entry of wangid {} is colour {}, but the Wang set has {} colours", where,
                                 kSlotNames[s], format_wang_id(id), id[std::size_t(s)], colours));
  return id[std::size_t(s)] - 1;
}

void unused(const WangId& id, int first, const std::string& where, std::string_view type) {
  for (int s = first; s < 8; s += 2)
    if (id[std::size_t(s)] != 0)
      throw InputError(
          fmt::format("{}: wangid {} sets the {} entry in a {} set (a mixed tile); Tilekit reads "
                      "corner sets with corner entries only and edge sets with edge entries only",
                      where, format_wang_id(id), kSlotNames[s], type));
}

}  // namespace

CornerTile corner_tile_of(const WangId& id, std::uint32_t colours, const std::string& where) {
  unused(id, kTop, where, "corner");
  return {needed(id, kTopRight, colours, where), needed(id, kBottomRight, colours, where),
          needed(id, kBottomLeft, colours, where), needed(id, kTopLeft, colours, where)};
}

WangTile wang_tile_of(const WangId& id, std::uint32_t colours, const std::string& where) {
  unused(id, kTopRight, where, "edge");
  return {needed(id, kTop, colours, where), needed(id, kRight, colours, where), needed(id, kBottom, colours, where),
          needed(id, kLeft, colours, where)};
}

std::string format_wang_id(const WangId& id) {
  return fmt::format("{}", fmt::join(id, ","));
}

WangId parse_wang_id(std::string_view text, const std::string& where) {
  WangId id{};
  auto bad = [&](std::string_view why) {
    return InputError(fmt::format("{}: wangid \"{}\" {}", where, text.substr(0, 64), why));
  };
  if (text.starts_with("0x") || text.starts_with("0X"))
    throw bad("is in the hexadecimal form of Tiled before 1.5; open and save the file in Tiled 1.5 or later");
  const char* p = text.data();
  const char* const stop = text.data() + text.size();
  for (std::size_t s = 0; s < 8; ++s) {
    if (s > 0) {
      if (p == stop || *p != ',') throw bad("needs eight comma-separated numbers");
      ++p;
    }
    const auto [end, ec] = std::from_chars(p, stop, id[s]);
    if (ec != std::errc{} || end == p) throw bad("needs eight comma-separated numbers");
    if (id[s] > kMaxTiledColours) throw bad(fmt::format("has an entry above {}", kMaxTiledColours));
    p = end;
  }
  if (p != stop) throw bad("has more than eight entries");
  return id;
}

}  // namespace tilekit::tilemap
