#pragma once
// The temporary files and folders of the running job (the `.NAME.tmpXXXXXX` beside each output
// of base/atomic_file.hpp), in one registry, so that nothing a signal interrupts stays on the
// disk. Each owner removes its own as it unwinds (RAII); the CLI's last step on an interrupted
// or failed run, remove_all(), removes whatever an owner could not (a temp file handed over by
// AtomicFileWriter::finish_temp() and not yet renamed). A command that does not poll for signals
// removes them from its signal handler (remove_all_in_signal_handler) before it exits.
#include <cstddef>
#include <string>

namespace tilekit {

class TempFiles {
 public:
  static void add(const std::string& path);     // a temp file or folder now exists
  static void forget(const std::string& path);  // renamed into place or removed by its owner
  // Removes every registered file and folder (whole); returns how many there were.
  static std::size_t remove_all();
  static std::size_t count();
  // The same, with system calls only, from a signal handler (base/signals.hpp
  // exit_on_signal_after_cleanup): the process ends right after, so the registry stays as it is.
  static void remove_all_in_signal_handler();
};

}  // namespace tilekit
