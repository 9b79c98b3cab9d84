#pragma once
// The one way to build a conversion result, so that every caller labels soundness alike: a thesis
// ch. 8 construction (aperiodic/convert.hpp), optionally pruned (aperiodic/prune.hpp), and labelled
// with the soundness of the whole chain source -> result. `aperiodic convert`, the table checks and
// the smallest-set search all call build_conversion(); label_by_decision() adds what a decision run
// (aperiodic/verify.hpp) found about the result.
#include <optional>
#include <string>

#include "aperiodic/convert.hpp"
#include "aperiodic/prune.hpp"
#include "aperiodic/verify.hpp"
#include "tilesets/tile_set.hpp"

namespace tilekit {

struct ConversionSpec {
  ConversionMethod method = ConversionMethod::Diagonal;
  SubdivisionOptions subdivision;
  int prune = -1;  // surround radius of the pruning; -1: no pruning
  int prune_patch = 1;  // > 1: then patches of that radius too, to a fixed point (prune_wang)
};

struct LabelledConversion {
  ConversionSpec spec;
  Conversion conversion;            // the construction's own result and label
  TileSet set;                      // the result, pruned when asked: SOURCE-METHOD[+merge-centres][-prunedR]
  std::optional<PruneReport> pruned;
  Soundness soundness = Soundness::Unverified;  // of the chain source -> set
  std::string argument;             // one line: why this label
  std::string prune_argument;       // pruned: what pruning removed and why it keeps the label
};

// "diagonal", "subdivision+merge-centres", ...
std::string spec_name(const ConversionSpec& spec);

// Converts, prunes and labels. InputError for an empty source or one of the wrong kind.
LabelledConversion build_conversion(const TileSet& source, const ConversionSpec& spec);

// A periodic tiling of the result overrides any label: a translation construction that is not a
// bijection between tilings can turn an aperiodic set into a periodic one, and a conjugate
// result of a periodic source is periodic too.
void label_by_decision(LabelledConversion& c, const VerifyResult& v);

}  // namespace tilekit
