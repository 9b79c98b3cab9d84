#pragma once
// SIGTERM, SIGINT and SIGUSR1 (Slurm's warning before the wall-time kill) ask a long search
// to stop, write its checkpoint and exit with code 3. A signal handler can only set a flag;
// this flag is the one piece of process-wide state in Tilekit, and it is only read.
namespace tilekit {

class SignalCatcher {
 public:
  // Installs the handlers and clears the flag; a catcher made while another is alive (e.g.
  // solve() inside a command that catches signals itself) only joins it.
  SignalCatcher();
  ~SignalCatcher();  // the outermost one restores the previous handlers
  SignalCatcher(const SignalCatcher&) = delete;
  SignalCatcher& operator=(const SignalCatcher&) = delete;
  // The signal number caught since construction, or 0.
  static int caught();
  // Installs the handlers for the rest of the process (never restored): a command that
  // checkpoints calls it first thing in main(), before any slow start-up work, so that a
  // signal at any moment, exit included, is caught rather than killing the process.
  static void catch_for_process();
};

}  // namespace tilekit
