#pragma once
// What `tilekit pack` is asked to do, as a value: the problem (complete set or a given set),
// the method and mode, the search's identity (formulation, ordering, group, seed, shard,
// portfolio candidates) and the run's settings (threads, limits, files). Its identity goes into
// every checkpoint, so that `tilekit pack --resume FILE` alone continues the run.
#include <cstdint>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "solver/problem.hpp"
#include "solver/run_settings.hpp"

namespace tilekit {

struct PackRequest {
  // ---- identity: fixed by a checkpoint (with run.seed and run.shard) ----
  std::string kind;  // "corner" | "wang" (the complete set over `colours`) | "window" (de Bruijn tori)
  std::int64_t colours = 0;
  std::string window;           // kind window: the window KxL (the torus is `size`)
  std::string set, size;        // or: a tile set (built-in name or file) and ROWSxCOLS
  std::string method = "auto";  // auto (database, construction, search) | search | construct
  std::string mode = "first";   // first | count | all
  Formulation formulation = Formulation::Auto;
  std::string ordering = "auto";
  std::string impose;                   // search only packings invariant under this group
  std::string lift;                     // search only colour-quotient lifts (solver/colour_lift_model.hpp SPEC)
  bool plain = false;                   // first mode: no portfolio, the plain search alone
  std::vector<std::string> candidates;  // portfolio candidates (empty = the default list)
  std::int64_t subproblems = 0;         // the split's subproblem target (0 = auto: 1024, 64 per shard)
  // ---- run settings: free to change on resume, except run.seed and run.shard ----
  // The seconds between checkpoints; not given: 300 s with a checkpoint file (run.checkpoint_path,
  // else run.resume_path, which a resumed run keeps checkpointing to), else none. It sets
  // run.checkpoint_every.
  std::optional<double> checkpoint_every;
  RunSettings run = [] {
    RunSettings r;
    r.progress = r.catch_signals = true;
    return r;
  }();
  std::string db;               // results database ("" = the default one)
  std::string portfolio_stats;  // "" = the default statistics file
  // First mode: the command's own file of the packing found (`pack --out`), written before the
  // packing is stored (SolutionSink::before_first_store). Not part of a checkpoint.
  std::function<void(const Tiling&)> write_found;
};

// The identity fields as JSON (what a checkpoint stores, with the database path).
nlohmann::json request_identity(const PackRequest& r);

// The fields of a request that a resumed run takes from its checkpoint unless the caller set
// them: the identity fields, and the time limit.
enum class PackField {
  Kind,
  Colours,
  Window,
  Set,
  Size,
  Method,
  Mode,
  Formulation,
  Ordering,
  Impose,
  Lift,
  Plain,
  Candidates,
  Subproblems,
  Seed,
  Shard,
  TimeLimit,
};
// Every PackField, in the order above.
const std::vector<PackField>& pack_fields();
// The field's name in messages (base/error.hpp's RequestError): "kind", "colours", "time_limit".
std::string_view pack_field_name(PackField f);
// The fields the caller set itself (the CLI: the flags given).
using PackFields = std::set<PackField>;

// `pack --resume FILE` with the request stored in FILE: the stored identity fills every field
// not in `given`; a given field that differs is a RequestError naming the field, its value here
// and in the checkpoint. A stored database path is used unless `here` names one, and a stored
// time limit unless TimeLimit is given.
PackRequest resume_request(const PackRequest& here, const PackFields& given, const nlohmann::json& stored,
                           const std::string& checkpoint);

}  // namespace tilekit
