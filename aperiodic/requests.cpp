#include "aperiodic/requests.hpp"

#include <fmt/format.h>

#include "aperiodic/json.hpp"
#include "aperiodic/store.hpp"
#include "base/error.hpp"

namespace tilekit {

VerifyReport run_verify(const VerifyRequest& r) {
  VerifyReport rep;
  rep.set = resolve_tile_set(r.set, &rep.repeated);
  if (rep.set.empty()) throw InputError(fmt::format("tile set '{}' has no tiles", r.set));
  if (r.prune >= 0) {
    PruneReport p;
    const std::string name = rep.set.name();
    rep.set = prune(rep.set, r.prune, &p);
    rep.set.set_name(fmt::format("{}-pruned{}", name, r.prune));
    rep.pruned = p;
  }
  if (rep.set.empty()) {
    // Surround pruning keeps every tiling of the plane and SCC pruning keeps tileability:
    // nothing left means the set does not tile the plane.
    rep.result.verdict = "finite";
    rep.result.route = "prune";
    rep.result.threads = 0;
  } else {
    rep.result = verify_tile_set(rep.set, r.options);
  }
  if (!r.db.empty()) {
    ResultsDb db(r.db);
    rep.run_id = store_verify(db, rep.set, rep.result,
                              {{"route", r.options.route},
                               {"time_limit", r.options.time_limit},
                               {"max_period", r.options.max_period},
                               {"max_square", r.options.max_square},
                               {"prune", r.prune}});
  }
  return rep;
}

ConvertReport run_convert(const ConvertRequest& r) {
  ConvertReport rep;
  rep.source = resolve_tile_set(r.set, &rep.repeated);
  rep.conversion = build_conversion(rep.source, r.spec);
  if (r.verify) {
    rep.verify = verify_tile_set(rep.conversion.set, r.verify_options);
    label_by_decision(rep.conversion, *rep.verify);
  }
  if (r.before_store) r.before_store(rep);
  if (!r.db.empty()) {
    ResultsDb db(r.db);
    nlohmann::json details = conversion_json(rep.conversion, rep.source.name());
    if (rep.verify) details["verify"] = verify_json(*rep.verify);
    rep.conversion_id = store_conversion(db, rep.source, rep.conversion.set, spec_name(r.spec),
                                         soundness_name(rep.conversion.soundness), details);
  }
  return rep;
}

}  // namespace tilekit
