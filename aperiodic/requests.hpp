#pragma once
// `tilekit aperiodic verify` and `convert` as library calls, so the CLI keeps only flags and
// printing. Each resolves the set (repeated tiles accepted and reported, the distinct set
// used), runs the engine, and stores what it found when a database is named.
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "aperiodic/conversion.hpp"
#include "aperiodic/verify.hpp"
#include "tilesets/tile_set_io.hpp"

namespace tilekit {

struct VerifyRequest {
  std::string set;  // built-in name or tile-set file
  int prune = -1;   // verify the set pruned to this radius (aperiodic/prune.hpp); -1: as it is
  VerifyOptions options;
  std::string db;   // results database ("" = none)
};

struct VerifyReport {
  TileSet set;  // the distinct tiles verified (pruned when asked)
  std::vector<RepeatedTile> repeated;
  std::optional<PruneReport> pruned;
  VerifyResult result;
  std::int64_t run_id = 0;  // with a database
};

VerifyReport run_verify(const VerifyRequest& r);

struct ConvertReport;

struct ConvertRequest {
  std::string set;
  ConversionSpec spec;
  bool verify = false;  // also verify the result (a periodic witness relabels it `periodic`)
  VerifyOptions verify_options;
  std::string db;
  // The command's other outputs (a tile-set file), written before the database is: a failed
  // write leaves the database as it was.
  std::function<void(const ConvertReport&)> before_store;
};

struct ConvertReport {
  TileSet source;
  std::vector<RepeatedTile> repeated;
  LabelledConversion conversion;
  std::optional<VerifyResult> verify;
  std::int64_t conversion_id = 0;  // with a database
};

ConvertReport run_convert(const ConvertRequest& r);

}  // namespace tilekit
