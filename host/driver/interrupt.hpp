// Clean interruption: while an InterruptHandling is alive, SIGINT and SIGTERM
// only ask the run to stop; the run loop finishes its step, writes a
// checkpoint, a last snapshot and run.json, and exits 130 / 143. A second
// signal ends the process at once (the files written so far stay whole:
// every file is written through a rename, and CSV rows in one write); the
// same signal repeated within half a second counts as one (GNU timeout and
// batch schedulers deliver it to the process and to its group).
#pragma once

namespace mfsd {

class InterruptHandling {
 public:
  InterruptHandling();   // installs the handlers
  ~InterruptHandling();  // restores the previous ones
  InterruptHandling(const InterruptHandling&) = delete;
  InterruptHandling& operator=(const InterruptHandling&) = delete;
};

// The signal that asked the run to stop (SIGINT, SIGTERM), or 0.
int interrupt_signal();
// Asks the run to stop as a signal would (e.g. from a language binding).
void request_interrupt(int signal);
// Forgets a request (a new run).
void clear_interrupt();

}  // namespace mfsd
