#include "aperiodic/table_checks.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <chrono>

#include "aperiodic/conversion.hpp"
#include "tilesets/tile_set_io.hpp"

namespace tilekit {

std::string verdict_text(const VerifyResult& v) {
  if (v.period) return fmt::format("periodic ({}x{} torus)", v.period->first, v.period->second);
  if (v.verdict == "unknown" && v.transducer)
    return fmt::format("unknown: no period <= {} rows / {} columns", v.transducer->k_rows, v.transducer->k_columns);
  return v.verdict;
}

VerifyResult verify_for_table(const TileSet& set, const VerifyOptions& o, bool transducer) {
  VerifyOptions torus = o;
  torus.route = "torus";
  torus.time_limit = 0;  // as the table always did: every shape up to max_period, exhaustively
  VerifyResult r = verify_tile_set(set, torus);
  if (!r.route.empty() || !transducer) return r;
  VerifyOptions t = o;
  t.route = "transducer";
  VerifyResult d = verify_tile_set(set, t);
  if (!d.route.empty()) return d;  // decided: periodic or finite
  r.transducer = d.transducer;
  return r;
}

CellCheck check_table_cell(const std::string& source, ConversionMethod m, const std::string& thesis,
                           const TableCheckOptions& o) {
  CellCheck c;
  c.source = source;
  c.method = method_name(m);
  c.thesis = thesis;
  const TileSet src = resolve_tile_set(source);
  const LabelledConversion plain = build_conversion(src, {m, {}, -1});
  const LabelledConversion pruned = build_conversion(src, {m, {}, o.prune});
  // The soundness of the chain to the pruned set (the verdicts cover both forms). Sets with a
  // sound chain are aperiodic: only the others go on to the transducer method.
  c.soundness = pruned.soundness;
  const bool sound = c.soundness == Soundness::Conjugate || c.soundness == Soundness::Lifts;
  c.tiles = plain.set.size();
  c.plain = verify_for_table(plain.set, o.verify, !sound);
  c.pruned_tiles = pruned.set.size();
  if (!pruned.set.empty()) c.pruned = verify_for_table(pruned.set, o.verify, !sound && !c.plain.period);
  else c.pruned.verdict = "finite";
  const bool periodic = c.plain.period || c.pruned.period;
  const VerifyResult& wit = c.plain.period ? c.plain : c.pruned;
  if (thesis == "failed") {
    if (periodic) c.status = "agrees", c.claim = fmt::format("thesis: failed. Agrees: the set tiles periodically, {}", verdict_text(wit));
    else if (sound) c.status = "false", c.claim = fmt::format("thesis: failed. But the construction is {}: the set is aperiodic", soundness_name(c.soundness));
    else c.status = "open", c.claim = fmt::format("thesis: failed. {}; not proven either way", verdict_text(c.plain));
  } else {
    std::string who = thesis.empty() ? "no thesis claim" : "thesis claims aperiodic";
    if (periodic)
      c.status = thesis.empty() ? "periodic" : "false",
      c.claim = fmt::format("{}. {}: {}", who, thesis.empty() ? "Not aperiodic" : "FALSE", verdict_text(wit));
    else if (sound) c.status = "holds", c.claim = fmt::format("{}. Holds: {} chain from {}", who, soundness_name(c.soundness), source);
    else c.status = "open", c.claim = fmt::format("{}. Not refuted ({}), not proven", who, verdict_text(c.plain));
  }
  return c;
}

TableRun run_table(const TableOptions& t, const TableCheckOptions& o, bool verify) {
  auto t0 = std::chrono::steady_clock::now();
  TableRun run;
  run.tables = compute_tables(t);
  if (verify) {
    const std::array<ConversionMethod, 5> methods = {ConversionMethod::Diagonal, ConversionMethod::Horizontal,
                                                     ConversionMethod::Vertical, ConversionMethod::Rotation,
                                                     ConversionMethod::Subdivision};
    TablesReport& r = run.tables;
    for (std::size_t si = 0; si < table_sources().size(); ++si) {
      const TableSource& s = table_sources()[si];
      if (s.name.empty()) continue;
      for (std::size_t mi = 0; mi < methods.size(); ++mi) {
        run.checks.push_back(check_table_cell(s.name, methods[mi], r.tables[0].cells[si][mi].thesis, o));
        const CellCheck& c = run.checks.back();
        if (c.status != "agrees") continue;
        // A thesis "failed" that the checks confirm: explained in Tables 8.1/8.2 and in the
        // iteration table of the same method (8.4 horizontal, 8.7 vertical).
        for (Table& tab : r.tables) {
          if (tab.id == "8.1" || tab.id == "8.2") {
            tab.cells[si][mi].explained = true;
            tab.cells[si][mi].note = c.claim;
          }
          bool h = methods[mi] == ConversionMethod::Horizontal && tab.id == "8.4";
          bool v = methods[mi] == ConversionMethod::Vertical && tab.id == "8.7";
          if ((h || v) && tab.cells.size() > 1 && tab.cells[1][si].differs) {
            tab.cells[1][si].explained = true;
            tab.cells[1][si].note = c.claim;
          }
        }
      }
    }
    r.unexplained = 0;
    for (auto& tab : r.tables)
      for (auto& row : tab.cells)
        for (auto& e : row) r.unexplained += e.differs && !e.explained;
  }
  const auto t1 = std::chrono::steady_clock::now();
  run.seconds = std::chrono::duration<double>(t1 - t0).count();
  if (verify) {
    run.smallest = smallest_aperiodic_corner_set();
    run.smallest_verify = verify_for_table(run.smallest->set, o.verify, false);
    run.smallest_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
  }
  return run;
}

}  // namespace tilekit
