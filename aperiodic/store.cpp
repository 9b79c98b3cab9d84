#include "aperiodic/store.hpp"

#include <fmt/format.h>

#include "base/hash.hpp"
#include "tilesets/tile_set_io.hpp"

namespace tilekit {

std::string tile_set_content_hash(const TileSet& set) {
  std::string text = std::string(kind_name(set.kind())) + "\n";
  for (std::size_t k = 0; k < set.size(); ++k) text += fmt::format("{}\n", fmt::join(set.file_colours(k), " "));
  return fmt::format("{:016x}", fnv1a64(text));
}

std::int64_t store_tile_set(ResultsDb& db, const TileSet& set) {
  return db.add_tileset(set.name(), set.kind(), set.size(), set.colours(), tile_set_content_hash(set), set.source(),
                        format_tile_set_text(set));
}

std::int64_t store_conversion(ResultsDb& db, const TileSet& source, const TileSet& result, const std::string& method,
                              const std::string& soundness, const nlohmann::json& details) {
  std::int64_t s = store_tile_set(db, source), r = store_tile_set(db, result);
  return db.add_conversion(s, method, r, source.size(), result.size(), result.colours(), soundness, details);
}

std::int64_t store_verify(ResultsDb& db, const TileSet& set, const VerifyResult& v, const nlohmann::json& params) {
  store_tile_set(db, set);
  RunRecord run;
  run.command = "aperiodic verify";
  run.params = params;
  run.params["set"] = set.name();
  run.params["content_hash"] = tile_set_content_hash(set);
  run.params["verdict"] = v.verdict;
  run.status = "running";
  run.threads = v.threads;
  run.id = db.begin_run(run);
  if (v.witness_tiling) {
    SolutionRecord s;
    s.run_id = run.id;
    s.tiling = *v.witness_tiling;
    s.method = v.route == "torus" ? "search" : "transducer";
    s.validated = v.witness_validated;  // checked by the validator in verify_tile_set()
    db.add_solution(s);
    run.solutions = 1;
  }
  run.status = v.interrupted                                       ? "interrupted"
               : v.verdict == "inconclusive" || v.verdict == "unknown" ? "incomplete"
                                                                     : "complete";
  run.nodes = v.nodes;
  run.seconds = v.seconds;
  db.finish_run(run);
  return run.id;
}

}  // namespace tilekit
