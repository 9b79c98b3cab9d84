#include "solver/run_trace.hpp"

#include "base/atomic_file.hpp"

namespace tilekit {

void RunTrace::add(std::string line) {
  std::lock_guard lock(mu_);
  lines_.push_back(std::move(line));
}

void RunTrace::write() {
  std::string text;
  {
    std::lock_guard lock(mu_);
    for (const std::string& l : lines_) {
      text += l;
      text += '\n';
    }
  }
  write_file_atomic(path_, text);
}

std::size_t RunTrace::lines() const {
  std::lock_guard lock(mu_);
  return lines_.size();
}

}  // namespace tilekit
