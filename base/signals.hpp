#pragma once
// SIGTERM, SIGINT and SIGUSR1 (Slurm's warning before the wall-time kill) ask a long search
// to stop, write its checkpoint and exit with code 3. A signal handler can only set a flag;
// this flag is the one piece of process-wide state in Tilekit, and it is only read.
//
// Every long job stops the same way (base/run_control.hpp): it polls caught() (or calls
// throw_if_interrupted() at its safe points), writes its checkpoint where it has one, lets its
// temporary files go (base/temp_files.hpp) and throws Interrupted with interrupted_message(),
// the one line on stderr before exit code 3.
#include <string>
#include <string_view>

namespace tilekit {

class SignalCatcher {
 public:
  // Installs the handlers and clears the flag; a catcher made while another is alive (e.g.
  // solve() inside a command that catches signals itself) only joins it.
  SignalCatcher();
  ~SignalCatcher();  // the outermost one restores the previous handlers and clears the flag
  SignalCatcher(const SignalCatcher&) = delete;
  SignalCatcher& operator=(const SignalCatcher&) = delete;
  // The signal number caught since construction, or 0.
  static int caught();
  // Installs the handlers for the rest of the process (never restored): a command that
  // checkpoints calls it first thing in main(), before any slow start-up work, so that a
  // signal at any moment, exit included, is caught rather than killing the process.
  static void catch_for_process();
};

// For a command that does not poll for signals (a short one: an export, a picture, an atlas):
// SIGTERM or SIGINT removes the temporary files it has registered (base/temp_files.hpp), prints
// "tilekit: interrupted by SIGTERM: nothing kept" and exits 3 at once, so that no hidden temp
// file stays. A SignalCatcher made later (a search inside the command) replaces it while it lives.
void exit_on_signal_after_cleanup();

// "SIGTERM", "SIGINT", "SIGUSR1", or "signal N".
std::string signal_name(int sig);

// The one line an interrupted job ends with: "interrupted by SIGTERM: KEPT", where `kept` says
// what stays on disk ("checkpoint written to F (continue with --resume F)", "nothing kept").
std::string interrupted_message(int sig, std::string_view kept);

// Throws Interrupted(interrupted_message(sig, "nothing kept")) once a signal was caught: the safe
// point of a job without a checkpoint (a point set, a tile set), whose temporary files are then
// removed as the exception unwinds. Inside parallel_for it ends the loop (base/parallel.hpp).
void throw_if_interrupted();

}  // namespace tilekit
