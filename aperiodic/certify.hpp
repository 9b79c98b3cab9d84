#pragma once
// Certificates of aperiodicity (`tilekit aperiodic certify`): a recorded chain (aperiodic/smallest.hpp)
// re-derived from its published source and written out with every link's map and inverse as
// explicit tables, for a checker that shares no code with this one (certificate/check.hpp,
// `aperiodic check-certificate`; the format is in certificate/README.md):
//   blocks       the 2x2 blocks (the pegs are the source's tile numbers);
//   symmetry     the image under a symmetry of the square, tile for tile (the canonical forms the
//                search applies its steps to are such images, renamed);
//   to-wang      the pair colours of each direction;
//   translation  the peg colours, the prune rounds (each removed tile is the centre of no
//                (2r+1) x (2r+1) patch of the tiles still there) and the lift table: the source
//                tile at a column from the 2N+1 columns of pegs around it, N the least radius at
//                which the windows of the source's rows give their centre back;
//   merge        the composite of the colour merges as classes, and the recovery table at the
//                least radius (then margin) at which it is a conjugacy: the original colour of
//                every neighbourhood of the merged set that is the image of the middle of a patch
//                of the source (`margin` pegs wider); every patch of the merged set `merged_margin`
//                pegs wider than the recovery of one cell reads must have its neighbourhoods there.
// Only links that the checker can check are written; another step is an InputError naming it.
#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>

#include "aperiodic/smallest.hpp"

namespace tilekit {

struct CertifyOptions {
  int max_lift_radius = 12;   // of the translation's lift table
  int max_merge_radius = 3;   // of the merge's recovery table
  int max_merge_margin = 2;   // of the patches of the source the table is read from
  int max_merged_margin = 3;  // of the merged set's patches, past the source's margin
};

// The certificate of the recorded chain (InputError: a step without a certificate form, or no
// table within the bounds; std::logic_error: the re-derived set is not the recorded one).
nlohmann::json certify_chain(const RecordedChain& record, const CertifyOptions& options = {});

}  // namespace tilekit
