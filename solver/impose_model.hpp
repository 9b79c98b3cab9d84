#pragma once
// The search model of a packing (or periodic tiling) under an imposed group G: the variables
// are the sites of the fundamental domain (impose_domain.hpp), one per G-orbit of pegs (corner)
// or edges (Wang), and the engine (dfs.hpp, parallel_search.hpp) searches it like every other
// model, with threads, shards, restarts, checkpoints and progress.
//
// Why this model is fast: under G a packing is a few hundred site values whose tile windows
// must hit distinct tile orbits. The model keeps, for every site that is the last unassigned
// one of some representative cell ("tight"), the set of its values whose completed tile orbit
// is still unused. That is forward checking on orbit availability: an empty set fails the node
// at once. Branching takes the tight site with the fewest values (most-constrained-first; ties
// by scan order), and partial-pattern counts (a pigeonhole bound: the incomplete cells that
// already show a pattern cannot outnumber the unused tile orbits with that pattern) prune
// further. Values come in a seeded order that is a function of the assignment (a Zobrist-style
// hash of it), so that a decision path replays to the same node, as the engine requires.
#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "solver/impose_domain.hpp"
#include "solver/model.hpp"
#include "solver/search_stats.hpp"

namespace tilekit {

class ImposeModel {
 public:
  enum class Ordering { Static, MostConstrained };
  // `pattern_sizes`: bit k set = slot subsets of size k (1..3) get demand/avail counts
  // (default 4: pairs; measured in BENCHMARKS.md, "Packings by search").
  ImposeModel(FundamentalDomain domain, Ordering ordering, unsigned pattern_sizes = 4);

  int branch(std::vector<int>& values);
  bool assign(int site, int value);
  void unassign(int site, int value);
  void set_value_seed(std::uint64_t seed) { value_seed_ = seed; }
  Tiling tiling() const;
  std::uint64_t multiplicity() const { return 1; }
  // Propagations and prunes (no-such-tile, orbit-used, pattern-count); solver/search_stats.hpp.
  ModelStats& stats() { return stats_; }

  const FundamentalDomain& domain() const { return t_->domain; }
  int sites() const { return t_->domain.num_sites; }
  // The incremental state equals a recomputation from the site values (tests; O(cells)).
  bool check_state() const;

 private:
  ModelStats stats_;
  struct Occurrence {
    int cell;
    int mult;  // slots of that cell held by the site
    int mask;  // which slots (bit j = slot j)
  };
  // Partial patterns (slot subsets of a cell): demand_ counts incomplete representative cells
  // whose pattern is assigned, avail_ the unused tile orbits with that pattern, per class of the
  // pattern under G. demand <= avail must hold (pigeonhole).
  struct Pattern {
    int n = 0;
    int mask = 0;  // slots of the pattern
    std::array<int, 3> slots{};
    std::array<std::uint32_t, 3> mul{};
    int offset = 0;  // into pattern_class
  };
  struct Tables {  // immutable, shared by every copy of the model
    FundamentalDomain domain;
    Ordering ordering = Ordering::MostConstrained;
    std::vector<int> occ_start;
    std::vector<Occurrence> occ;
    std::vector<const std::uint8_t*> slot_perm;  // 4 per cell, into domain.perm_tables
    std::vector<int> slot_site;
    std::vector<std::uint32_t> slot_weight;
    std::vector<Pattern> patterns;
    std::vector<int> pattern_class;  // offset + code -> class index (into avail/demand)
    std::vector<int> avail_init;
  };
  static void build_patterns(Tables& t, unsigned pattern_sizes);

  bool apply_occurrence(const Occurrence& o, int site, int value);
  void revert_occurrence(const Occurrence& o, int site);
  void revert_site(int site, int upto);   // reverts occurrences [start, upto) of the site
  std::uint32_t tile_of(int cell) const;  // all four slots assigned
  std::uint32_t tile_with(const Occurrence& o, int value) const;
  int pattern_key(int cell, const Pattern& p) const;
  bool pattern_assigned(int cell, const Pattern& p) const {
    return (assigned_slots_[std::size_t(cell)] & p.mask) == p.mask;
  }
  std::uint64_t cell_mask(int cell, int site, std::uint64_t mask) const;
  std::uint64_t site_mask(int site) const;  // values of a site left by its tight cells
  int lone_unassigned(int cell) const;      // the only unassigned site of a cell, or -1
  void tight_add(int site);
  void tight_remove(int site);

  std::shared_ptr<const Tables> t_;
  std::uint64_t value_seed_ = 0;
  std::uint64_t hash_ = 0;                    // of the assignment: xor of mix_seed(site, value)
  std::vector<int> val_;                      // site -> value or -1
  std::vector<int> cu_;                       // cell -> unassigned slots
  std::vector<std::uint8_t> colour_;          // cell*4 + slot -> its colour (when assigned)
  std::vector<std::uint8_t> assigned_slots_;  // cell -> bit j set when slot j is assigned
  std::vector<int> trail_;                    // pattern classes touched by apply_occurrence, popped by revert
  std::vector<std::uint8_t> used_;            // tile orbit -> used by a complete cell
  std::vector<int> tight_cnt_, tight_list_, tight_pos_;
  std::vector<int> avail_, demand_;
  int assigned_ = 0;
};

static_assert(SearchModel<ImposeModel>);

}  // namespace tilekit
