// Interruption: SIGINT, SIGTERM and SIGHUP held back while files are written, so that an
// interrupted run leaves either the earlier files or the complete new ones, never a
// temporary (reports/SCHEMA.md).
#pragma once

#include <signal.h>

namespace vivv {

// The signals that interrupt a run.
inline sigset_t interrupting_signals() {
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, SIGINT);
  sigaddset(&set, SIGTERM);
  sigaddset(&set, SIGHUP);
  return set;
}

// While alive, the interrupting signals wait; one that arrived meanwhile is delivered when
// it ends.
class DeferInterrupts {
 public:
  DeferInterrupts() {
    const sigset_t set = interrupting_signals();
    sigprocmask(SIG_BLOCK, &set, &previous_);
  }
  ~DeferInterrupts() { sigprocmask(SIG_SETMASK, &previous_, nullptr); }
  DeferInterrupts(const DeferInterrupts&) = delete;
  DeferInterrupts& operator=(const DeferInterrupts&) = delete;

 private:
  sigset_t previous_;
};

}  // namespace vivv
