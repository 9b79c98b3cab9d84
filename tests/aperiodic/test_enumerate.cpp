// The search over conversion chains (aperiodic/enumerate.hpp) and what it rests on: canonical
// forms up to symmetry, the steps' symmetry claims, strip pruning, determinism, shards, checkpoints.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <map>
#include <nlohmann/json.hpp>
#include <set>

#include "aperiodic/canonical.hpp"
#include "aperiodic/conversion_graph.hpp"
#include "aperiodic/decide.hpp"
#include "aperiodic/enumerate.hpp"
#include "aperiodic/prune.hpp"
#include "aperiodic/steps.hpp"
#include "base/atomic_file.hpp"
#include "base/checkpoint_envelope.hpp"
#include "base/error.hpp"
#include "cluster/schedule_sim.hpp"
#include "solver/run_trace.hpp"
#include "tests/cli_runner.hpp"
#include "tilesets/tile_set_io.hpp"

using namespace tilekit;
namespace fs = std::filesystem;

namespace {

// The same set with colours renamed (per direction) and tiles listed backwards.
TileSet renamed(const TileSet& s) {
  std::vector<WangTile> w;
  for (auto it = s.wang_tiles().rbegin(); it != s.wang_tiles().rend(); ++it)
    w.push_back({it->n * 7 + 3, it->e * 5 + 1, it->s * 7 + 3, it->w * 5 + 1});
  return TileSet::wang(w);
}

EnumerateOptions small_run() {
  EnumerateOptions o;
  o.sources = {"jeandel-rao-11-variant-2", "labbe-19"};
  o.max_depth = 2;
  o.max_tiles = 40;
  o.batch = 3;
  return o;
}

std::set<std::string> edge_keys(const EnumerateResult& r) {
  std::set<std::string> out;
  for (const auto& [k, e] : r.edges) out.insert(e.from + " " + e.step + " " + e.to + " " + e.label);
  return out;
}

}  // namespace

TEST(Canonical, ImagesUnderSymmetryAndRenamedColoursShareOneForm) {
  TileSet kari = resolve_tile_set("kari-14");
  const CanonicalForm f = canonical_form(kari);
  EXPECT_TRUE(f.exact);
  for (const Dihedral& g : Dihedral::all()) {
    EXPECT_EQ(canonical_form(transform(kari, g)).hash, f.hash) << g.name();
    EXPECT_EQ(canonical_form(renamed(transform(kari, g))).hash, f.hash) << g.name();
  }
  EXPECT_NE(canonical_form(resolve_tile_set("culik-13")).hash, f.hash);
  EXPECT_EQ(f.set.size(), kari.size());
  // The form is a tile set again, and reads back from its text.
  EXPECT_EQ(set_from_canonical_text(f.text, "test").name(), "enum-" + f.hash);
  EXPECT_THROW(set_from_canonical_text("wang\n1 2 3\n", "test"), InputError);
  EXPECT_THROW(set_from_canonical_text("hex\n1 2 3 4\n", "test"), InputError);
}

TEST(Canonical, FourQuarterTurnsAreTheIdentityAndAMirrorIsItsOwnInverse) {
  TileSet c = resolve_tile_set("labbe-19");
  TileSet t = c;
  for (int i = 0; i < 4; ++i) t = transform(t, Dihedral{1, false});
  EXPECT_EQ(t.wang_tiles(), c.wang_tiles());
  EXPECT_EQ(transform(transform(c, Dihedral{0, true}), Dihedral{0, true}).wang_tiles(), c.wang_tiles());
  EXPECT_THROW(Dihedral::parse("rot45"), InputError);
}

// steps.hpp applies most operations to one image only: this checks the claims it rests on.
TEST(Steps, OperationsCommuteWithTheSymmetriesTheSearchLeavesOut) {
  TileSet jr = resolve_tile_set("jeandel-rao-11-variant-2");
  for (const char* op :
       {"prune", "prune-strips", "rotation", "blocks", "subdivision", "diagonal", "horizontal", "fuse"}) {
    const std::vector<std::string> tried = symmetries_for(op);
    auto hash_of = [&](const std::string& step) {
      auto r = apply_step(jr, step);
      return r ? canonical_form(r->set).hash : std::string("none");
    };
    std::set<std::string> covered;
    for (const std::string& g : tried) covered.insert(hash_of(g == "id" ? op : g + ":" + op));
    for (const Dihedral& g : Dihedral::all())
      EXPECT_TRUE(covered.count(hash_of(g.name() + ":" + op))) << op << " " << g.name();
  }
}

TEST(Steps, LabelsAndBadSteps) {
  TileSet jr = resolve_tile_set("jeandel-rao-11-variant-2");
  auto rot = apply_step(jr, "rotation");
  ASSERT_TRUE(rot);
  EXPECT_EQ(rot->label, "conjugate");
  EXPECT_EQ(rot->set.kind(), TileKind::Corner);
  auto back = apply_step(rot->set, "to-wang");
  ASSERT_TRUE(back);
  EXPECT_EQ(back->set.size(), rot->set.size());
  EXPECT_FALSE(apply_step(jr, "to-wang"));  // a Wang set has no to-wang
  auto fused = apply_step(jr, "fuse");
  ASSERT_TRUE(fused);
  EXPECT_EQ(fused->label, "lifts");
  // blocks: one corner tile per 2x2 block of Wang tiles whose inner edges match (85 for this set),
  // and back to Wang tiles one for one.
  auto blocks = apply_step(jr, "blocks");
  ASSERT_TRUE(blocks);
  EXPECT_EQ(blocks->label, "conjugate");
  EXPECT_EQ(blocks->set.size(), 85u);
  EXPECT_FALSE(apply_step(blocks->set, "blocks"));
  // Two tiles that sit beside themselves only and above each other freely: a row of one over a
  // row of either, 4 blocks.
  const TileSet two = TileSet::wang({{0, 1, 0, 1}, {0, 0, 0, 0}});
  ASSERT_TRUE(apply_step(two, "blocks"));
  EXPECT_EQ(apply_step(two, "blocks")->set.size(), 4u);
  EXPECT_THROW(apply_step(jr, "squash"), InputError);
  EXPECT_THROW(apply_step(jr, "rot45:rotation"), InputError);
  EXPECT_TRUE(sound_label("prune"));
  EXPECT_FALSE(sound_label("unverified"));
}

// Strip pruning keeps every periodic tiling and tileability: it never empties an aperiodic set,
// and a periodic set keeps a periodic tiling.
TEST(StripPrune, KeepsAperiodicSetsAndPeriodicTilings) {
  for (const std::string& name : published_enumeration_sources()) {
    TileSet s = resolve_tile_set(name);
    PruneReport rep;
    TileSet p = prune_strips(s, 3, &rep);
    EXPECT_FALSE(p.empty()) << name;
    EXPECT_EQ(rep.after, p.size());
  }
  const std::string dir = std::string(TILEKIT_SOURCE_DIR) + "/aperiodic/data/";
  TileSet periodic = resolve_tile_set(dir + "periodic-7-30.tiles");
  TileSet p = prune_strips(periodic, 3);
  DecideOptions d;
  d.time_limit = 20;
  EXPECT_EQ(decide_tile_set(p, d).verdict, "periodic");
}

TEST(Enumerate, ResultsDoNotDependOnThreadsAndEveryChainReplays) {
  EnumerateOptions o = small_run();
  o.threads = 1;
  EnumerateResult one = enumerate_conversions(o);
  o.threads = 2;
  EnumerateResult two = enumerate_conversions(o);
  EXPECT_TRUE(one.complete);
  EXPECT_EQ(one.digest, two.digest);
  EXPECT_EQ(edge_keys(one), edge_keys(two));
  // Every set with a sound chain: its recorded chain replays from the source to the same hash.
  std::size_t checked = 0;
  for (const auto& [h, n] : one.nodes) {
    if (n.depth < 1 || n.kind != TileKind::Corner) continue;
    std::vector<ChainLink> chain = recorded_chain(one, h);
    std::vector<std::string> steps;
    for (std::size_t i = 1; i < chain.size(); ++i) steps.push_back(chain[i].step);
    std::vector<ReplayedLink> replay = replay_chain(chain.front().step, steps);
    EXPECT_EQ(replay.back().hash, h);
    for (const ReplayedLink& l : replay) EXPECT_TRUE(sound_label(l.label)) << l.step;
    ++checked;
  }
  EXPECT_GT(checked, 0u);
  // The per-source smallest sets are corner sets with a chain from their source.
  for (const SourceBest& b : smallest_per_source(conversion_graph(one))) {
    EXPECT_EQ(b.best.kind, "corner");
    EXPECT_EQ(replay_chain(b.source, b.chain.steps()).back().hash, b.best.hash);
  }
}

TEST(Enumerate, ShardsMergeToTheWholeRun) {
  EnumerateOptions o = small_run();
  EnumerateResult whole = enumerate_conversions(o);
  std::set<std::string> sets, edges;
  for (int i = 0; i < 3; ++i) {
    o.shard = {i, 3};
    EnumerateResult part = enumerate_conversions(o);
    for (const auto& [h, n] : part.nodes) sets.insert(h);
    for (const std::string& e : edge_keys(part)) edges.insert(e);
  }
  std::set<std::string> whole_sets;
  for (const auto& [h, n] : whole.nodes) whole_sets.insert(h);
  EXPECT_EQ(sets, whole_sets);
  EXPECT_EQ(edges, edge_keys(whole));
}

TEST(Enumerate, ResumesFromEveryBatchToTheSameResultAndRefusesBadCheckpoints) {
  test::TempDir d;
  EnumerateOptions o = small_run();
  const EnumerateResult whole = enumerate_conversions(o);
  // Stop after every batch (a time limit of zero would never stop; a tiny one stops at once).
  o.checkpoint_path = d / "c.ckpt";
  o.checkpoint_every = 0;
  o.time_limit = 1e-9;
  EnumerateResult r = enumerate_conversions(o);
  int runs = 1;
  while (!r.complete && runs < 200) {
    o.resume_path = o.checkpoint_path;
    r = enumerate_conversions(o);
    ++runs;
  }
  EXPECT_TRUE(r.complete);
  EXPECT_GT(runs, 2);
  EXPECT_EQ(r.digest, whole.digest);

  EnumerateOptions other = o;
  other.max_tiles = 41;
  EXPECT_THROW(enumerate_conversions(other), InputError);  // other options
  std::string text = test::slurp(o.checkpoint_path);
  text[text.size() / 2] ^= 1;
  write_file_atomic(d / "bad.ckpt", text);
  other = o;
  other.resume_path = d / "bad.ckpt";
  EXPECT_THROW(enumerate_conversions(other), InputError);  // corrupt
  write_file_atomic(d / "cut.ckpt", text.substr(0, text.size() / 3));
  other.resume_path = d / "cut.ckpt";
  EXPECT_THROW(enumerate_conversions(other), InputError);  // truncated
  other.resume_path = d / "missing.ckpt";
  EXPECT_THROW(enumerate_conversions(other), InputError);
}

// A checkpoint with a fresh checksum can still lie: one that relabels an unsound link as
// conjugate (so a periodic set gets a "sound" chain) is refused on resume, because every sound
// link is re-derived by its step before the run builds on it.
TEST(Enumerate, AResumedCheckpointThatRelabelsALinkAsSoundIsRefused) {
  test::TempDir d;
  EnumerateOptions o;  // one source, one step: a run of milliseconds with leads in it
  o.sources = {"jeandel-rao-11-variant-2"};
  o.max_depth = 1;
  o.max_tiles = 100;
  o.checkpoint_path = d / "c.ckpt";
  const EnumerateResult whole = enumerate_conversions(o);
  ASSERT_TRUE(whole.complete);
  const std::string text = test::slurp(o.checkpoint_path);
  nlohmann::json body = nlohmann::json::parse(open_checkpoint(text, "TILEKIT-ENUMERATE", 1, 1, "c.ckpt"));
  // An unsound edge into a set that has no sound chain (a lead), and its parent's depth.
  std::map<std::string, nlohmann::json*> node;
  for (auto& n : body["nodes"]) node[n[0].get<std::string>()] = &n;
  nlohmann::json* edge = nullptr;
  for (auto& e : body["edges"])
    if (!sound_label(e[3].get<std::string>()) && (*node.at(e[2].get<std::string>()))[2] == -1 &&
        (*node.at(e[0].get<std::string>()))[2] >= 0)
      edge = &e;
  ASSERT_NE(edge, nullptr) << "the small run has no lead to relabel";
  nlohmann::json& from = *node.at((*edge)[0].get<std::string>());
  nlohmann::json& to = *node.at((*edge)[2].get<std::string>());
  (*edge)[3] = "conjugate";
  to[2] = to[3] = from[2].get<int>() + 1;  // depth, owned depth
  to[5] = (*edge)[0];                      // parent
  to[6] = (*edge)[1];                      // step
  to[7] = "conjugate";
  to[8] = from[8];  // root
  to[9] = "";
  write_checkpoint_envelope(d / "lie.ckpt", "TILEKIT-ENUMERATE", 1, body.dump());
  EnumerateOptions resume = o;
  resume.checkpoint_path.clear();
  resume.resume_path = d / "lie.ckpt";
  try {
    enumerate_conversions(resume);
    FAIL() << "the relabelled checkpoint was resumed";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("re-derives to"), std::string::npos) << e.what();
  }
  // The honest checkpoint resumes to the same result.
  resume.resume_path = o.checkpoint_path;
  EXPECT_EQ(enumerate_conversions(resume).digest, whole.digest);
}

TEST(Enumerate, BadOptionsAreInputErrors) {
  EnumerateOptions o = small_run();
  o.sources = {"penrose-2"};
  EXPECT_THROW(enumerate_conversions(o), InputError);
  o = small_run();
  o.max_depth = -1;
  EXPECT_THROW(enumerate_conversions(o), InputError);
  o = small_run();
  o.shard = {3, 3};
  EXPECT_THROW(enumerate_conversions(o), InputError);
  o = small_run();
  o.time_limit = -1;
  EXPECT_THROW(enumerate_conversions(o), InputError);
}

// `aperiodic enumerate --trace`: one line per set expanded, its steps as pieces, and the
// scheduling simulator replays it (cluster/schedule_sim.hpp, cost = seconds).
TEST(Enumerate, TraceHasALinePerSetExpandedThatTheSimulatorReplays) {
  test::TempDir d;
  EnumerateOptions o = small_run();
  o.max_depth = 1;
  o.threads = 2;
  const std::string path = d / "enum.jsonl";
  o.trace = std::make_shared<RunTrace>(path);
  const EnumerateResult r = enumerate_conversions(o);
  ASSERT_TRUE(r.complete);
  std::ifstream in(path);
  std::string line;
  std::size_t searches = 0, units = 0;
  std::set<std::uint64_t> indices;
  while (std::getline(in, line)) {
    const nlohmann::json j = nlohmann::json::parse(line);
    if (j["type"] == "search") {
      ++searches;
      continue;
    }
    ASSERT_EQ(j["type"], "subproblem");
    ++units;
    indices.insert(j["index"].get<std::uint64_t>());
    EXPECT_EQ(j["nodes"].get<std::size_t>(), j["pieces"].size());
    EXPECT_GT(j["nodes"].get<std::size_t>(), 0u);
    double sum = 0;
    for (const auto& p : j["pieces"]) sum += p[1].get<double>();
    EXPECT_LE(sum, j["seconds"].get<double>() * (1 + 1e-5) + 1e-6);  // 6 significant digits each
  }
  EXPECT_EQ(searches, 1u);
  EXPECT_EQ(units, r.expanded);
  EXPECT_EQ(indices.size(), units);
  const cluster::Trace t = cluster::read_trace({path}, "seconds");
  EXPECT_EQ(t.units.size(), units);
  const cluster::SimResult one = cluster::simulate(t, cluster::SchedulePolicy::Pool, 1);
  EXPECT_NEAR(one.efficiency, 1.0, 1e-9);
}
