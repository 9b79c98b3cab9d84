#include "aperiodic/enumerate.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "aperiodic/canonical.hpp"
#include "aperiodic/decide.hpp"
#include "aperiodic/steps.hpp"
#include "aperiodic/store.hpp"
#include "base/checkpoint_envelope.hpp"
#include "base/error.hpp"
#include "base/hash.hpp"
#include "base/parse.hpp"
#include "base/json_input.hpp"
#include "base/parallel.hpp"
#include "base/progress.hpp"
#include "base/signals.hpp"
#include "checkpoints/checkpoint.hpp"
#include "results/results_db.hpp"
#include "solver/run_trace.hpp"
#include "tilesets/tile_set_io.hpp"

namespace tilekit {

namespace {

using Clock = std::chrono::steady_clock;
constexpr std::string_view kMagic = "TILEKIT-ENUMERATE";
constexpr int kVersion = 1;

// One result of expanding a set: what a worker computes, merged in order afterwards.
struct Child {
  std::string step, label, argument;
  std::optional<CanonicalForm> form;  // empty: over max_tiles (counted) or not applicable
  std::string lead;                   // unverified results: the decision
};

std::string operation_of(const std::string& step) {
  const auto colon = step.find(':');
  return colon == std::string::npos ? step : step.substr(colon + 1);
}

// Every step of one set, in a fixed order.
const std::vector<std::string>& operations_of(const EnumerateOptions& o) {
  return o.operations.empty() ? step_operations() : o.operations;
}

std::vector<std::string> steps_of(TileKind kind, const std::vector<std::string>& operations) {
  std::vector<std::string> steps;
  for (const std::string& op : operations) {
    const bool corner_only = op == "to-wang" || op.rfind("merge-colours", 0) == 0;
    const bool wang_only = !corner_only && op != "prune" && op != "prune-strips" && op != "prune5";
    if ((corner_only && kind == TileKind::Wang) || (wang_only && kind == TileKind::Corner)) continue;
    for (const std::string& g : symmetries_for(op)) steps.push_back(g == "id" ? op : g + ":" + op);
  }
  return steps;
}

// The decision of a lead: the transducer route bounded by k (no clock), so that every run agrees.
std::string decide_lead(const TileSet& set, int max_k, std::string* label) {
  DecideOptions d;
  d.time_limit = 0;
  d.max_k = max_k;
  d.memory_limit = std::size_t(1) << 30;
  DecideResult r = decide_tile_set(set, d);
  if (r.verdict == "periodic") {
    *label = "periodic";
    return fmt::format("periodic: a {}x{} torus tiling (validated)", r.period_rows, r.period_cols);
  }
  if (r.verdict == "finite") {
    *label = "finite";
    return fmt::format("finite: no strip of {} {}", r.k, r.direction);
  }
  return r.stopped_by == "max-k" ? fmt::format("unknown at k={}", max_k)
                                 : fmt::format("unknown at k={} ({})", r.k, r.stopped_by);
}

// Stops between steps when `stop` asks (the batch is then dropped and redone on resume). With
// `pieces`, each step's seconds (for the trace).
std::vector<Child> expand(const TileSet& set, const EnumerateOptions& o, const std::function<bool()>& stop,
                          std::vector<double>* pieces = nullptr) {
  std::vector<Child> out;
  for (const std::string& step : steps_of(set.kind(), operations_of(o))) {
    if (stop()) return out;
    const auto t0 = Clock::now();
    struct Timed {  // every way out of this step
      std::vector<double>* pieces;
      Clock::time_point t0;
      ~Timed() {
        if (pieces) pieces->push_back(std::chrono::duration<double>(Clock::now() - t0).count());
      }
    } timed{pieces, t0};
    std::optional<StepResult> r;
    try {
      r = apply_step(set, step);  // a long step (a merge search, a 5x5 prune) stops on a signal
    } catch (const Interrupted&) {
      if (!stop()) throw;  // stop() records the signal, and the batch is dropped
      return out;
    }
    if (!r) continue;
    Child c{step, r->label, r->argument, std::nullopt, {}};
    if (r->set.size() <= o.max_tiles) {
      c.form = canonical_form(r->set);
      if (c.label == "unverified") {
        std::string label = c.label;
        c.lead = decide_lead(r->set, o.lead_max_k, &label);
        c.label = label;
      }
    }
    out.push_back(std::move(c));
  }
  return out;
}

std::string fingerprint(const EnumerateOptions& o, const std::vector<std::string>& sources) {
  return nlohmann::json{{"format", "tilekit-enumerate"},
                        {"sources", sources},
                        {"max_depth", o.max_depth},
                        {"max_tiles", o.max_tiles},
                        {"batch", o.batch},
                        {"shard", fmt::format("{}/{}", o.shard.index, o.shard.count)},
                        {"lead_max_k", o.lead_max_k},
                        {"steps", operations_of(o)}}
      .dump();
}

std::uint64_t hash_value(const std::string& hex) {
  return std::stoull(hex, nullptr, 16);
}

// The search state between batches: what the checkpoint holds.
struct State {
  std::string fingerprint;
  EnumerateResult r;
  double seconds = 0;
};

nlohmann::json encode_state(const State& s) {
  nlohmann::json nodes = nlohmann::json::array(), edges = nlohmann::json::array();
  for (const auto& [h, n] : s.r.nodes)
    nodes.push_back({n.hash, n.text, n.depth, n.owned_depth, n.expanded, n.parent, n.step, n.label, n.root, n.lead});
  for (const auto& [k, e] : s.r.edges) edges.push_back({e.from, e.step, e.to, e.label, e.argument});
  return {{"fingerprint", s.fingerprint}, {"seconds", s.seconds}, {"batches", s.r.batches}, {"expanded", s.r.expanded},
          {"over_limit", s.r.over_limit}, {"nodes", nodes},       {"edges", edges}};
}

// The body of a checkpoint, after base/checkpoint_envelope.hpp checked the envelope.
State decode_state(std::string_view body, const std::string& origin) {
  State s;
  try {
    const nlohmann::json doc = parse_json_input(body, origin);
    const JsonIn j(doc, origin);
    s.fingerprint = j.at("fingerprint").string();
    s.seconds = j.at("seconds").number(0);
    s.r.batches = j.at("batches").unsigned_integer();
    s.r.expanded = j.at("expanded").unsigned_integer();
    const JsonIn over = j.at("over_limit");
    for (const std::string& op : all_step_operations())
      if (over.has(op)) s.r.over_limit[op] = over.at(op).unsigned_integer();
    const JsonIn nodes = j.at("nodes");
    for (std::size_t i = 0, n = nodes.array(); i < n; ++i) {
      const JsonIn x = nodes[i];
      x.array(10, 10);
      EnumNode node;
      node.hash = x[0].string(16);
      node.text = x[1].string();
      TileSet set = set_from_canonical_text(node.text, origin);
      if (set.name() != "enum-" + node.hash) throw x[0].error("the hash does not match the tile set");
      node.kind = set.kind();
      node.tiles = set.size();
      node.colours = set.colours();
      node.depth = int(x[2].integer(-1, 1000));
      node.owned_depth = int(x[3].integer(-1, 1000));
      node.expanded = int(x[4].integer(-1, 1000));
      node.parent = x[5].string();
      node.step = x[6].string();
      node.label = x[7].string();
      node.root = x[8].string();
      node.lead = x[9].string();
      if (!s.r.nodes.emplace(node.hash, node).second) throw x[0].error("a set listed twice");
    }
    const JsonIn edges = j.at("edges");
    for (std::size_t i = 0, n = edges.array(); i < n; ++i) {
      const JsonIn x = edges[i];
      x.array(5, 5);
      EnumEdge e{x[0].string(), x[1].string(), x[2].string(), x[3].string(), x[4].string()};
      if (!s.r.nodes.count(e.from) || !s.r.nodes.count(e.to)) throw x.error("an edge between unknown sets");
      s.r.edges[{e.from, e.step}] = e;
    }
    for (const auto& [h, n] : s.r.nodes)
      if (!n.parent.empty() && !s.r.nodes.count(n.parent))
        throw InputError(fmt::format("{}: a set's parent is unknown", origin));
  } catch (const InputError& e) {
    throw InputError(fmt::format("checkpoint {}: {}", origin, e.what()));
  }
  return s;
}

State read_state(const std::string& path) {
  return decode_state(read_checkpoint_envelope(path, kMagic, kVersion, kVersion), path);
}

// A checkpoint's claims re-derived before a resumed run builds on them: every published set is
// its source's canonical form at depth 0, every sound edge is what its step gives (set and label,
// apply_step again), and every set's shortest sound link is such an edge, one deeper than its
// parent. The envelope's checksum only catches damage, not a relabelled node written with a fresh
// checksum, so a checkpoint that claims a link its step does not give is refused here (InputError
// naming the link). Unsound edges are not re-derived: they only ever make a set a lead.
void rederive_state(const State& s, const std::vector<std::string>& sources, int threads, const std::string& origin) {
  auto refuse = [&](const std::string& what) {
    throw InputError(fmt::format("checkpoint {}: {} (the checkpoint is refused: its links must re-derive)", origin, what));
  };
  const EnumerateResult& r = s.r;
  for (const auto& [h, n] : r.nodes) {
    if (n.label == "published") {
      if (std::find(sources.begin(), sources.end(), n.root) == sources.end())
        refuse(fmt::format("set {} claims the source '{}', which is not one of this run's", h, n.root));
      if (canonical_form(resolve_tile_set(n.root)).hash != h || n.depth != 0 || !n.parent.empty())
        refuse(fmt::format("set {} is not the published set {}", h, n.root));
      continue;
    }
    if (n.parent.empty()) {
      if (n.depth >= 0) refuse(fmt::format("set {} has depth {} but no link", h, n.depth));
      continue;
    }
    auto e = r.edges.find({n.parent, n.step});
    const EnumNode& p = r.nodes.at(n.parent);
    if (e == r.edges.end() || e->second.to != h || e->second.label != n.label || !sound_label(n.label) ||
        p.depth < 0 || n.depth != p.depth + 1 || n.root != p.root)
      refuse(fmt::format("the link {} -[{}]-> {} ({}) is not a recorded sound edge one deeper than its parent",
                         n.parent, n.step, h, n.label));
  }
  std::vector<const EnumEdge*> sound;
  for (const auto& [k, e] : r.edges)
    if (sound_label(e.label)) sound.push_back(&e);
  std::vector<std::string> wrong(sound.size());
  parallel_for(std::int64_t(sound.size()), threads, [&](std::int64_t i) {
    const EnumEdge& e = *sound[std::size_t(i)];
    const EnumNode& from = r.nodes.at(e.from);
    std::optional<StepResult> x = apply_step(set_from_canonical_text(from.text, origin), e.step);
    const std::string hash = x ? canonical_form(x->set).hash : std::string();
    if (!x || x->label != e.label || hash != e.to)
      wrong[std::size_t(i)] = fmt::format("the link {} -[{}]-> {} ({}) re-derives to {}", e.from, e.step, e.to,
                                          e.label, x ? hash + " (" + x->label + ")" : std::string("nothing"));
  });
  for (const std::string& w : wrong)
    if (!w.empty()) refuse(w);
}

std::string digest_of(const EnumerateResult& r) {
  StableHash h;
  for (const auto& [hash, n] : r.nodes) h.add("S " + hash + " " + n.label + "\n");
  for (const auto& [k, e] : r.edges) h.add("E " + e.from + " " + e.step + " " + e.to + " " + e.label + "\n");
  return fmt::format("{:016x}", h.fnv());
}

// Rows for the results database; source text is the same in every run and shard.
void store_batch(ResultsDb& db, const EnumerateResult& r, const std::vector<std::string>& node_hashes,
                 const std::vector<EnumEdge>& edges) {
  std::map<std::string, std::int64_t> id;
  auto set_id = [&](const std::string& hash) {
    if (auto it = id.find(hash); it != id.end()) return it->second;
    const EnumNode& n = r.nodes.at(hash);
    TileSet set = set_from_canonical_text(n.text, "enumerate");
    set.set_source(n.label == "published" ? "published: " + n.root : "aperiodic enumerate");
    return id[hash] = store_tile_set(db, set);
  };
  for (const std::string& h : node_hashes) set_id(h);
  for (const EnumEdge& e : edges) {
    const EnumNode &a = r.nodes.at(e.from), &b = r.nodes.at(e.to);
    db.add_conversion(set_id(e.from), e.step, set_id(e.to), a.tiles, b.tiles, b.colours, e.label,
                      {{"argument", e.argument}});
  }
}

// A set first reached: what a node knows of it before any chain is attached.
EnumNode new_node(const CanonicalForm& f) {
  EnumNode n;
  n.hash = f.hash;
  n.text = f.text;
  n.kind = f.set.kind();
  n.tiles = f.set.size();
  n.colours = f.set.colours();
  return n;
}

// The published sources as the nodes of depth 0.
void add_sources(EnumerateResult& r, const std::vector<std::string>& sources, std::vector<std::string>& new_nodes) {
  for (const std::string& name : sources) {
    CanonicalForm f = canonical_form(resolve_tile_set(name));
    auto [it, added] = r.nodes.emplace(f.hash, EnumNode{});
    EnumNode& n = it->second;
    if (added) {
      n = new_node(f);
      n.root = name;
      n.label = "published";
      new_nodes.push_back(f.hash);
    }
    n.depth = n.owned_depth = 0;
  }
}

// One expanded set's children merged into the graph: new sets and edges (recorded for the
// database), the shortest sound chain to each set, and the depth this shard owns it at.
void merge_children(EnumerateResult& r, const std::string& parent_hash, std::vector<Child>& children,
                    const EnumerateOptions& o, std::vector<std::string>& new_nodes, std::vector<EnumEdge>& new_edges,
                    std::size_t& best_corner) {
  EnumNode& parent = r.nodes.at(parent_hash);
  parent.expanded = parent.owned_depth;
  ++r.expanded;
  const bool from_root = parent.label == "published";
  for (Child& c : children) {
    if (!c.form) {
      ++r.over_limit[operation_of(c.step)];
      continue;
    }
    const CanonicalForm& f = *c.form;
    auto [it, added] = r.nodes.emplace(f.hash, EnumNode{});
    EnumNode& n = it->second;
    if (added) {
      n = new_node(f);
      new_nodes.push_back(f.hash);
    }
    EnumEdge e{parent.hash, c.step, f.hash, c.label,
               c.lead.empty() ? c.argument : c.argument + "; decision: " + c.lead};
    auto [eit, eadded] = r.edges.emplace(std::pair{e.from, e.step}, e);
    if (eadded) new_edges.push_back(e);
    if (!sound_label(c.label)) {
      if (n.depth < 0 && n.lead.empty()) n.lead = c.lead.empty() ? c.label : c.lead;
      continue;
    }
    const int d = parent.depth + 1;
    if (n.depth < 0 || d < n.depth) {
      n.depth = d;
      n.parent = parent.hash;
      n.step = c.step;
      n.label = c.label;
      n.root = parent.root;
      n.lead.clear();
    }
    const bool owned = !from_root || o.shard.owns(hash_value(f.hash));
    if (owned && parent.owned_depth >= 0 && (n.owned_depth < 0 || parent.owned_depth + 1 < n.owned_depth))
      n.owned_depth = parent.owned_depth + 1;
    if (n.kind == TileKind::Corner && (best_corner == 0 || n.tiles < best_corner)) best_corner = n.tiles;
  }
}

// The trace's lines of one batch (enumerate.hpp, "Trace").
void trace_batch(RunTrace& trace, const EnumerateOptions& o, std::size_t batch_number, const std::vector<EnumNode>& batch,
                 const std::vector<std::vector<Child>>& children, const std::vector<std::vector<double>>& pieces,
                 const std::vector<double>& seconds) {
  for (std::size_t i = 0; i < batch.size(); ++i) {
    std::string p;
    for (double s : pieces[i]) p += fmt::format("{}[1,{:.6g}]", p.empty() ? "" : ",", s);
    trace.add(fmt::format(
        R"({{"type":"subproblem","title":"aperiodic enumerate","index":{},"path":"set {} depth {}","owner":"{}","nodes":{},"seconds":{:.6g},"solutions":{},"resumed":false,"batch":{},"pieces":[{}]}})",
        batch_number * o.batch + i, batch[i].hash, batch[i].owned_depth, shard_text(o.shard), pieces[i].size(),
        seconds[i], children[i].size(), batch_number, p));
  }
}

// The run's sources, after every option is checked (InputError naming the first bad one).
std::vector<std::string> checked_sources(const EnumerateOptions& o) {
  if (o.max_depth < 0) throw RequestError("max_depth", fmt::format("`max_depth` must be >= 0, got {}", o.max_depth));
  if (o.max_tiles < 1) throw RequestError("max_tiles", "`max_tiles` must be >= 1");
  if (o.batch < 1) throw RequestError("batch", "`batch` must be >= 1");
  if (!o.shard.valid())
    throw RequestError("shard",
                       fmt::format("`shard` {}/{}: expected I/N with 0 <= I < N", o.shard.index, o.shard.count));
  if (o.lead_max_k < 1)
    throw RequestError("lead_max_k", fmt::format("`lead_max_k` must be >= 1, got {}", o.lead_max_k));
  if (!(o.time_limit >= 0) || !std::isfinite(o.time_limit))
    throw RequestError("time_limit",
                       fmt::format("`time_limit` must be a number of seconds >= 0, got {}", o.time_limit));
  if (!(o.checkpoint_every >= 0) || !std::isfinite(o.checkpoint_every))
    throw RequestError("checkpoint_every",
                       fmt::format("`checkpoint_every` must be a number of seconds >= 0, got {}", o.checkpoint_every));
  std::vector<std::string> sources = o.sources.empty() ? published_enumeration_sources() : o.sources;
  const auto& known = published_enumeration_sources();
  for (const std::string& s : sources)
    if (std::find(known.begin(), known.end(), s) == known.end())
      throw InputError(
          fmt::format("unknown source '{}' (expected published aperiodic Wang sets: {})", s, fmt::join(known, ", ")));
  for (const std::string& op : o.operations)
    if (std::find(all_step_operations().begin(), all_step_operations().end(), op) == all_step_operations().end())
      throw RequestError("operations", fmt::format("`operations`: unknown step operation '{}' (expected some of: {})",
                                                   op, fmt::join(all_step_operations(), ", ")));
  return sources;
}

}  // namespace

// Sources with a proof of aperiodicity only: jeandel-rao-11-variant-3 (Fig. 10 of Jeandel and Rao)
// differs from Fig. 3 in one tile, is equivalent to neither Fig. 3 nor Fig. 4, and what the paper
// proves about it is not established here (tilesets/data/README.md), so no chain starts from it.
const std::vector<std::string>& published_enumeration_sources() {
  static const std::vector<std::string> s = {"jeandel-rao-11", "jeandel-rao-11-variant-2", "kari-14", "culik-13",
                                             "ammann-gs-16", "labbe-19"};
  return s;
}

EnumerateResult enumerate_conversions(const EnumerateOptions& o) {
  const std::vector<std::string> sources = checked_sources(o);
  const int threads = resolve_threads(o.threads);

  const auto t0 = Clock::now();
  const Deadline deadline(o.time_limit, t0);
  std::optional<SignalCatcher> signals;
  if (o.catch_signals) signals.emplace();
  State st;
  st.fingerprint = fingerprint(o, sources);
  if (!o.resume_path.empty()) {
    State old = read_state(o.resume_path);
    if (std::string diff = fingerprint_difference(st.fingerprint, old.fingerprint); !diff.empty())
      throw InputError(fmt::format("checkpoint {} does not match this run: {}", o.resume_path, diff));
    rederive_state(old, sources, threads, o.resume_path);
    st = std::move(old);
    st.r.resumed = true;
  }
  EnumerateResult& r = st.r;
  std::optional<ResultsDb> db;
  if (!o.db.empty()) db.emplace(o.db);
  std::map<std::string, TileSet> sets;  // canonical sets in memory, by hash
  auto set_of = [&](const EnumNode& n) -> const TileSet& {
    auto it = sets.find(n.hash);
    if (it == sets.end()) it = sets.emplace(n.hash, set_from_canonical_text(n.text, "enumerate")).first;
    return it->second;
  };
  std::vector<std::string> new_nodes;
  std::vector<EnumEdge> new_edges;
  if (!r.resumed) add_sources(r, sources, new_nodes);
  if (o.trace)
    o.trace->add(fmt::format(
        R"({{"type":"search","title":"aperiodic enumerate","mode":"count","subproblems":0,"threads":{},"owner":"{}","split_nodes":0,"resumed":{}}})",
        threads, shard_text(o.shard), r.resumed));

  auto pending = [&] {
    std::vector<const EnumNode*> p;
    for (const auto& [h, n] : r.nodes)
      if (n.owned_depth >= 0 && n.owned_depth < o.max_depth && n.tiles <= o.max_tiles &&
          (n.expanded < 0 || n.expanded > n.owned_depth))
        p.push_back(&n);
    std::sort(p.begin(), p.end(), [](const EnumNode* a, const EnumNode* b) {
      return std::tuple(a->tiles, a->kind, a->hash) < std::tuple(b->tiles, b->kind, b->hash);
    });
    return p;
  };
  auto elapsed = [&] { return std::chrono::duration<double>(Clock::now() - t0).count(); };
  const double before = st.seconds;
  auto last_checkpoint = Clock::now();
  auto save = [&] {
    if (db) {
      store_batch(*db, r, new_nodes, new_edges);
      new_nodes.clear();
      new_edges.clear();
    }
    if (o.trace) o.trace->write();
    if (o.checkpoint_path.empty()) return;
    st.seconds = before + elapsed();
    write_checkpoint_envelope(o.checkpoint_path, kMagic, kVersion, encode_state(st).dump());
    ++r.checkpoints;
    last_checkpoint = Clock::now();
  };
  ProgressReporter progress("enumerate", 0, o.progress);
  std::size_t best_corner = 0, batches_here = 0;
  for (;;) {
    std::vector<const EnumNode*> queue = pending();
    if (queue.empty()) {
      r.complete = true;
      break;
    }
    if (o.catch_signals && SignalCatcher::caught()) {
      r.interrupted = true;
      r.signal = SignalCatcher::caught();
      break;
    }
    // Each run finishes one batch at least, so that a short limit still makes progress.
    const Deadline limit = batches_here > 0 ? deadline : Deadline();
    if (limit.expired()) {
      r.timed_out = true;
      break;
    }
    const std::size_t take = std::min(o.batch, queue.size());
    std::vector<EnumNode> batch;
    for (std::size_t i = 0; i < take; ++i) batch.push_back(*queue[i]);
    std::vector<const TileSet*> batch_sets;
    for (const EnumNode& n : batch) batch_sets.push_back(&set_of(n));
    std::vector<std::vector<Child>> children(batch.size());
    std::vector<std::vector<double>> pieces(o.trace ? batch.size() : 0);
    std::vector<double> seconds(batch.size(), 0.0);
    // A signal or the time limit in the middle of a batch drops the batch: the state stays that of
    // the last batch boundary, which the checkpoint below records.
    StopToken stop;
    auto stopping = [&] { return poll_stop(stop, limit, o.catch_signals); };
    parallel_for(
        std::int64_t(batch.size()), threads,
        [&](std::int64_t i) {
          const auto t = Clock::now();
          const std::size_t k = std::size_t(i);
          children[k] = expand(*batch_sets[k], o, stopping, o.trace ? &pieces[k] : nullptr);
          seconds[k] = std::chrono::duration<double>(Clock::now() - t).count();
        },
        &stop);
    if (stop.requested()) {
      r.interrupted = stop.reason() == StopReason::Signal;
      r.signal = r.interrupted ? SignalCatcher::caught() : 0;
      r.timed_out = stop.reason() == StopReason::TimeLimit;
      break;
    }
    if (o.trace) trace_batch(*o.trace, o, r.batches, batch, children, pieces, seconds);
    // Merge in batch order, steps in order: the same state whatever the threads did.
    for (std::size_t i = 0; i < batch.size(); ++i)
      merge_children(r, batch[i].hash, children[i], o, new_nodes, new_edges, best_corner);
    ++r.batches;
    ++batches_here;
    progress.update(double(r.expanded), double(r.expanded + queue.size() - take),
                    fmt::format("{} sets, {} edges, smallest sound corner set {}", r.nodes.size(), r.edges.size(),
                                best_corner == 0 ? std::string("-") : std::to_string(best_corner)));
    if (std::chrono::duration<double>(Clock::now() - last_checkpoint).count() >= o.checkpoint_every) save();
  }
  progress.finish();
  save();
  r.digest = digest_of(r);
  r.seconds = elapsed();
  r.total_seconds = before + r.seconds;
  return r;
}

std::vector<ChainLink> recorded_chain(const EnumerateResult& r, const std::string& hash) {
  std::vector<ChainLink> chain;
  for (std::string h = hash; !h.empty();) {
    const EnumNode& n = r.nodes.at(h);
    std::string argument;
    if (auto it = r.edges.find({n.parent, n.step}); it != r.edges.end()) argument = it->second.argument;
    chain.push_back({n.hash, n.step, n.label, argument, {}, n.tiles, n.colours, n.kind});
    if (n.depth < 0) throw InputError(fmt::format("set {} has no sound chain", hash));
    h = n.parent;
  }
  std::reverse(chain.begin(), chain.end());
  const std::string source = r.nodes.at(chain.front().hash).root;
  chain.front().step = source;
  chain.front().derivation = {source, {}};
  std::vector<std::string> steps;
  for (std::size_t i = 1; i < chain.size(); ++i) {
    steps.push_back(chain[i].step);
    chain[i].derivation = {source, steps};
  }
  return chain;
}

std::vector<ReplayedLink> replay_chain(const std::string& source, const std::vector<std::string>& steps,
                                       TileSet* last, const Deadline& deadline, bool* timed_out) {
  const auto& known = published_enumeration_sources();
  if (std::find(known.begin(), known.end(), source) == known.end())
    throw InputError(fmt::format("unknown source '{}' (expected one of: {})", source, fmt::join(known, ", ")));
  CanonicalForm f = canonical_form(resolve_tile_set(source));
  std::vector<ReplayedLink> out;
  out.push_back(
      {source, "published", resolve_tile_set(source).source(), f.hash, f.set.size(), f.set.colours(), f.set.kind()});
  if (timed_out) *timed_out = false;
  for (const std::string& step : steps) {
    if (deadline.expired()) {
      if (!timed_out) throw CanonicalTimeLimit();
      *timed_out = true;
      break;
    }
    std::optional<StepResult> r = apply_step(f.set, step);
    if (!r)
      throw InputError(fmt::format("step '{}' does not apply to set {} ({} {} tiles)", step, f.hash, f.set.size(),
                                   kind_name(f.set.kind())));
    try {
      f = canonical_form(r->set, 512, deadline);
    } catch (const CanonicalTimeLimit&) {
      if (!timed_out) throw;
      *timed_out = true;
      break;
    }
    out.push_back({step, r->label, r->argument, f.hash, f.set.size(), f.set.colours(), f.set.kind()});
  }
  if (last) *last = f.set;
  return out;
}

}  // namespace tilekit
