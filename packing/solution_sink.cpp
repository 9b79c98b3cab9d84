// SolutionSink: batched, validated solutions into the results database (solution_sink.hpp).
#include "packing/solution_sink.hpp"

#include <utility>

namespace tilekit {

SolutionSink::SolutionSink(ResultsDb& db, std::int64_t run_id, const TilingProblem& p)
    : db_(db), run_id_(run_id), sym_(PackingSymmetry::for_problem(p)) {}

void SolutionSink::add(const Tiling& t) {
  SolutionRecord s;
  s.run_id = run_id_;
  s.tiling = t;
  s.method = method;
  s.validated = true;  // solve() validates every solution before emitting it
  s.group = group;
  if (sym_) {
    // The translates of one leaf arrive one after another and share their canonical form.
    Tiling normal = sym_->normal_form(t);
    if (normal.cells != last_normal_) {
      last_normal_ = normal.cells;
      last_hash_ = solution_hash(sym_->canonical(normal, &last_orbit_));
    }
    s.canonical_hash = last_hash_;
    s.orbit_size = last_orbit_;
  }
  batch_.push_back(std::move(s));
  if (batch_.size() >= 50000) flush();
}

void SolutionSink::flush() {
  if (!batch_.empty() && before_first_store) std::exchange(before_first_store, nullptr)(batch_.front().tiling);
  added_ += db_.add_solutions(batch_);
  batch_.clear();
}

}  // namespace tilekit
