#pragma once
// The checks behind `tilekit aperiodic table`: every corner set of thesis Table 8.1 (and its
// pruned form) verified, each thesis claim judged against the verdicts and the soundness of its
// construction, the thesis' "failed" entries that turn out periodic marked as explained in the
// tables, and the smallest corner set with a sound chain verified as well.
#include <optional>
#include <string>
#include <vector>

#include "aperiodic/smallest.hpp"
#include "aperiodic/table.hpp"
#include "aperiodic/verify.hpp"

namespace tilekit {

struct CellCheck {
  std::string source, method, thesis;
  std::size_t tiles = 0, pruned_tiles = 0;
  Soundness soundness = Soundness::Unverified;  // of the chain to the pruned set
  VerifyResult plain, pruned;
  std::string claim;   // the thesis' claim and what the checks say about it
  std::string status;  // holds, false, agrees, periodic, open
};

struct TableCheckOptions {
  VerifyOptions verify;  // per set (the transducer route, then the torus route up to max_period)
  int prune = 3;
};

struct TableRun {
  TablesReport tables;
  std::vector<CellCheck> checks;  // empty with verify off
  std::optional<CornerSetCandidate> smallest;
  VerifyResult smallest_verify;
  double seconds = 0;           // the tables and their checks
  double smallest_seconds = 0;  // re-deriving and verifying the smallest set (aperiodic/smallest.hpp)
};

// "periodic (3x2 torus)", "no-period-up-to 8", "unknown: no period <= 14 rows / 12 columns".
std::string verdict_text(const VerifyResult& v);

// Verifies one set for the table: the torus route up to max_period, exhaustively (as the table
// always did, so its figures stay), then, when that decides nothing and `transducer` is set, the
// transducer route within o.time_limit (a decision replaces "no-period-up-to P").
VerifyResult verify_for_table(const TileSet& set, const VerifyOptions& o, bool transducer);

CellCheck check_table_cell(const std::string& source, ConversionMethod m, const std::string& thesis,
                           const TableCheckOptions& o);

TableRun run_table(const TableOptions& t, const TableCheckOptions& o, bool verify);

}  // namespace tilekit
