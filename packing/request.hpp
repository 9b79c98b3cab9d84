#pragma once
// What `tilekit pack` is asked to do, as a value: the problem (complete set or a given set),
// the method and mode, the search's identity (formulation, ordering, group, seed, shard,
// portfolio candidates) and the run's settings (threads, limits, files). Its identity goes into
// every checkpoint, so that `tilekit pack --resume FILE` alone continues the run.
#include <cstdint>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "solver/run_settings.hpp"

namespace tilekit {

struct PackRequest {
  // ---- identity: fixed by a checkpoint (with run.seed and run.shard) ----
  std::string kind;  // "corner" | "wang" (the complete set over `colours`)
  std::int64_t colours = 0;
  std::string set, size;        // or: a tile set (built-in name or file) and ROWSxCOLS
  std::string method = "auto";  // auto (database, construction, search) | search | construct
  std::string mode = "first";   // first | count | all
  std::string formulation = "auto", ordering = "auto";
  std::string impose;                   // search only packings invariant under this group
  std::string lift;                     // search only colour-quotient lifts (solver/colour_lift_model.hpp SPEC)
  bool plain = false;                   // first mode: no portfolio, the plain search alone
  std::vector<std::string> candidates;  // portfolio candidates (empty = the default list)
  // ---- run settings: free to change on resume, except run.seed and run.shard ----
  // run.checkpoint_every < 0: 300 s with a checkpoint file (run.checkpoint_path, else
  // run.resume_path, which a resumed run keeps checkpointing to), else none.
  RunSettings run = [] {
    RunSettings r;
    r.checkpoint_every = -1;
    r.progress = r.catch_signals = true;
    return r;
  }();
  std::string db;               // results database ("" = the default one)
  std::string portfolio_stats;  // "" = the default statistics file
};

// The identity fields as JSON (what a checkpoint stores, with the database path).
nlohmann::json request_identity(const PackRequest& r);

// The names of the identity fields as flags ("--kind", "--colors", ...), for messages.
const std::vector<std::string>& identity_flags();

// `pack --resume FILE` with the request stored in FILE: the stored identity fills every field
// whose flag was not given; a given flag that differs is an InputError naming the flag, its
// value here and in the checkpoint. A stored database path is used unless --db is given.
// `given` holds the flags given on the command line (e.g. "--mode").
PackRequest resume_request(const PackRequest& here, const std::set<std::string>& given, const nlohmann::json& stored,
                           const std::string& checkpoint);

}  // namespace tilekit
