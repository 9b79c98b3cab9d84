#pragma once
// SIGTERM, SIGINT and SIGUSR1 (Slurm's warning before the wall-time kill) ask a long search
// to stop, write its checkpoint and exit with code 3. A signal handler can only set a flag;
// this flag is the one piece of process-wide state in the solver, and it is only read.
namespace tilekit {

class SignalCatcher {
 public:
  SignalCatcher();   // installs the handlers (and clears the flag)
  ~SignalCatcher();  // restores the previous handlers
  SignalCatcher(const SignalCatcher&) = delete;
  SignalCatcher& operator=(const SignalCatcher&) = delete;
  // The signal number caught since construction, or 0.
  static int caught();
};

}  // namespace tilekit
