#pragma once
// Depth-first search over the fundamental domain of a SymmetricModel.
//
// Why this engine: under an imposed group a packing is a few hundred site values whose tile
// windows must hit distinct orbits. The search assigns one site at a time and keeps, for every
// site that is the last unassigned one of some representative cell ("tight"), the set of its
// values whose completed tile orbit is still unused. That is forward checking on orbit
// availability: an empty set fails the node at once. Branching takes the tight site with the
// fewest values (most-constrained-first; ties by scanline order), values in a seeded random
// order, and first-solution runs restart after a Luby-sequence node budget (Luby, Sinclair and
// Zuckerman 1993), as the prototype of DESIGN.md did with plain restarts.
#include <array>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <vector>

#include "solver/impose_model.hpp"

namespace tilekit {

struct SymmetricSearchConfig {
  bool random_values = true;  // seeded random value order (else ascending)
  bool most_constrained = true;  // MCF among tight sites (else scanline order)
  int pattern_sizes = 1 << 2;  // bit k: slot subsets of size k (1..3) get demand/avail counts
  std::uint64_t seed = 0;
};

class SymmetricSearch {
 public:
  enum class Outcome { Solution, Exhausted, NodeLimit, Stopped };

  SymmetricSearch(const SymmetricModel& model, const SymmetricSearchConfig& config);

  // One DFS from the empty assignment. Stops at the first solution unless `each` is given, in
  // which case every solution is passed to it (with the site values) and the run goes on.
  // node_limit 0 = none. `stop` (may be null) and `deadline` are polled every few thousand nodes.
  Outcome run(std::uint64_t node_limit, const std::atomic<bool>* stop,
              std::chrono::steady_clock::time_point deadline,
              const std::function<void(const std::vector<int>&)>& each = {});

  const std::vector<int>& values() const { return val_; }
  std::uint64_t nodes() const { return nodes_; }      // assignments tried, all runs together
  std::uint64_t solutions() const { return solutions_; }

 private:
  struct Occurrence {
    int cell;
    int mult;  // slots of that cell held by the site
  };
  struct Frame {
    int site = -1;
    int n = 0, i = 0;
    bool assigned = false;
    std::uint8_t vals[64];
  };

  // Partial patterns (slot subsets of a cell): demand_ counts incomplete representative cells
  // whose pattern is assigned, avail_ the unused tile orbits with that pattern, per class of the
  // pattern under G. demand <= avail must hold (pigeonhole; "counts of unused windows per
  // partial pattern").
  struct Pattern {
    int n = 0;
    int mask = 0;             // slots of the pattern
    std::array<int, 3> slots{};
    std::array<std::uint32_t, 3> mul{};
    int offset = 0;           // into pattern_class_
  };
  void reset();
  bool assign(int site, int v);
  bool apply_occurrence(int site, const Occurrence& o);
  void revert_occurrence(int site, const Occurrence& o);
  std::uint32_t tile_of(int cell) const;
  int pattern_key(int cell, const Pattern& p) const;
  bool pattern_assigned(int cell, const Pattern& p) const;
  int site_slots(int cell, int site) const;
  void build_patterns();
  void unassign(int site);
  bool select(Frame& f);
  std::uint64_t cell_mask(int cell, int site, std::uint64_t mask) const;
  int lone_unassigned(int cell) const;  // the only unassigned site of a cell, or -1
  void tight_add(int site);
  void tight_remove(int site);
  std::uint64_t next_random();

  const SymmetricModel& m_;
  SymmetricSearchConfig cfg_;
  std::uint64_t rng_;
  std::vector<int> occ_start_;
  std::vector<Occurrence> occ_;
  std::vector<const std::uint8_t*> slot_perm_;  // 4 per cell
  std::vector<int> slot_site_;
  std::vector<std::uint32_t> slot_weight_;

  std::vector<int> val_;
  std::vector<int> cu_;  // unassigned slots per cell
  std::vector<std::uint8_t> used_;
  std::vector<int> tight_cnt_, tight_list_, tight_pos_;
  std::vector<Pattern> patterns_;
  std::vector<int> pattern_class_;  // offset + code -> class index (into avail_/demand_)
  std::vector<int> avail_init_, avail_, demand_;
  std::vector<Frame> stack_;
  int assigned_ = 0;
  std::uint64_t nodes_ = 0, solutions_ = 0;
};

}  // namespace tilekit
