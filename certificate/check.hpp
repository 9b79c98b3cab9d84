#pragma once
// The independent checker of aperiodicity certificates (`tilekit aperiodic check-certificate`).
//
// A certificate (written by `aperiodic certify`, aperiodic/certify.hpp) states a published aperiodic
// Wang set and a chain of links to a corner set, each link with its map and the map's inverse as
// explicit tables. This checker shares no code with the search or the conversions: it reads the
// JSON itself and checks, for every link, that the two maps compose to the identity on every
// admissible neighbourhood (the argument per link is in check.cpp), so that the tilings of the
// last set are in bijection with those of the source by maps that commute with translations: the
// last set is aperiodic exactly when the source is. The format is in certificate/README.md.
#include <array>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace tilekit::certificate {

// A tile as four colours: Wang [n, e, s, w], corner [nw, ne, sw, se].
using Tile = std::array<std::uint32_t, 4>;

struct LinkReport {
  std::string op;  // blocks, symmetry, to-wang, translation, merge
  std::size_t from_tiles = 0, to_tiles = 0;
  std::string checked;  // what was enumerated and compared, in words
};

struct Report {
  bool accepted = false;
  std::string error;  // the first failed check (accepted false)
  std::string source;
  bool source_matches_reference = false;  // the stated source tiles equal the reference given
  std::size_t source_tiles = 0, result_tiles = 0;
  std::uint32_t result_colours = 0;
  std::vector<LinkReport> links;
};

// Checks a certificate. `reference`: the published source's tiles (Wang, [n, e, s, w], any order)
// as the caller read them from its own copy of the set; the stated source must equal them as a set
// (no renaming, no symmetry). Never throws for a bad certificate: the report names the failed check.
Report check(const nlohmann::json& certificate, const std::vector<Tile>& reference);

}  // namespace tilekit::certificate
