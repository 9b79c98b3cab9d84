#pragma once
// The smallest corner set that is *really* aperiodic: one whose aperiodicity follows from a
// chain of sound steps (aperiodic/steps.hpp: published, conjugate, lifts, prune) back to a
// published aperiodic Wang set. The chain is the best one a run of `aperiodic enumerate` found
// (aperiodic/enumerate.hpp); the run writes it as a record (`enumerate --record FILE`), and
// the record of the run reported in BENCHMARKS.md is aperiodic/data/smallest-chain.json,
// embedded in the binary. Nothing in the record is trusted: every link is re-derived from the
// published source by the same steps (replay_chain) and must give the recorded set and a sound
// label. The thesis claims 44 (Fig. 8.6); Nurmi (Bridges 2016) gives 30.
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "aperiodic/enumerate.hpp"
#include "tilesets/tile_set.hpp"

namespace tilekit {

struct ChainStep {
  std::string step;  // the source's name, then each step ("blocks", "rot90:horizontal", ...)
  std::string set;   // canonical hash of the set after this step
  std::size_t tiles = 0;
  std::uint32_t colours = 0;
  std::string kind;      // "wang" or "corner"
  std::string label;     // "published", "conjugate", "lifts" or "prune"
  std::string argument;  // why the step keeps aperiodicity
  LinkDerivation derivation;  // what re-derives this link (its set, label and tile count)
};

// A chain as a search recorded it: the source and the steps, the set they must give, and the
// run that found it (command, digest; what it expanded).
struct RecordedChain {
  std::string source;
  std::vector<std::string> steps;
  std::string set;  // canonical hash of the last set
  std::size_t tiles = 0;
  std::uint32_t colours = 0;
  std::string command, digest;  // how to rerun the search; its digest (aperiodic/enumerate.hpp)
  bool complete = false;        // the search exhausted its bounds
  std::size_t expanded = 0, sets = 0;
};

// The record of the least sound corner set of a search (NotFound when it reached none), with
// `command`, the caller's words for rerunning the search (the CLI: `tilekit aperiodic enumerate`
// and the options that change its results), and its parse (InputError naming the field for
// anything malformed).
nlohmann::json smallest_record(const std::string& command, const EnumerateResult& r);
RecordedChain parse_smallest_record(std::string_view text, const std::string& origin);

// The record embedded from aperiodic/data/smallest-chain.json.
RecordedChain embedded_smallest_record();

// One aperiodic corner set re-derived from its chain, with its provenance.
struct CornerSetCandidate {
  std::string source;
  std::size_t tiles = 0;
  std::uint32_t colours = 0;
  std::string soundness;  // the link labels after the source, distinct, joined by '+' ("conjugate+prune")
  std::vector<ChainStep> chain;
  TileSet set;
  RecordedChain record;
};

// Replays the record's steps from its source (aperiodic link) and checks every link: a sound
// label, and the last set is the recorded one (its tiles and colours), a corner set. Every
// failure is an InputError naming the link (a record is input: a file, a database row, or the
// embedded record after a change to a step), as is an unknown source or step.
CornerSetCandidate rederive_chain(const RecordedChain& record);

// Published aperiodic Wang sets (built-in names) of the thesis' tables.
const std::vector<std::string>& published_aperiodic_sets();

// rederive_chain(embedded_smallest_record()).
CornerSetCandidate smallest_aperiodic_corner_set();

}  // namespace tilekit
