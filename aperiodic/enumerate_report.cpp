#include "aperiodic/enumerate_report.hpp"

#include <tuple>

#include "aperiodic/canonical.hpp"
#include "aperiodic/table_checks.hpp"

namespace tilekit {

namespace {

// The least sound corner set (tiles, then colours, then hash), checked by the torus route.
SmallestFound check_smallest(const EnumerateResult& r, const EnumNode& best, const SmallestCheckOptions& o) {
  SmallestFound s;
  s.node = best;
  s.chain = recorded_chain(r, best.hash);
  s.set = set_from_canonical_text(best.text, "enumerate");
  VerifyOptions vo;
  vo.time_limit = o.verify_time_limit;
  vo.max_period = o.verify_period;
  s.check = verify_for_table(s.set, vo, false);
  return s;
}

}  // namespace

EnumerateReport enumerate_report(const EnumerateResult& r, const SmallestCheckOptions& o) {
  EnumerateReport rep;
  const EnumNode* best = nullptr;
  for (const auto& [h, n] : r.nodes) {
    if (n.depth >= 0) {
      ++rep.depth[n.depth].first;
      if (n.expanded >= 0) ++rep.depth[n.depth].second, ++rep.expanded_by_source[n.root];
      if (n.kind == TileKind::Corner &&
          (!best || std::tuple(n.tiles, n.colours, n.hash) < std::tuple(best->tiles, best->colours, best->hash)))
        best = &n;
    } else if (n.lead.rfind("unknown", 0) == 0) {
      rep.leads.push_back(n);
    }
  }
  rep.graph = conversion_graph(r);
  rep.per_source = smallest_per_source(rep.graph);
  if (best) rep.smallest = check_smallest(r, *best, o);
  return rep;
}

}  // namespace tilekit
