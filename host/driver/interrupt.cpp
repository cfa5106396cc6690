#include "host/driver/interrupt.hpp"

#include <unistd.h>

#include <csignal>
#include <ctime>

namespace mfsd {

namespace {

volatile std::sig_atomic_t pending = 0;
struct timespec first_at {};
struct sigaction previous_int, previous_term;

double seconds_since(const struct timespec& t0) {
  struct timespec t {};
  clock_gettime(CLOCK_MONOTONIC, &t);  // async-signal-safe
  return double(t.tv_sec - t0.tv_sec) + 1e-9 * double(t.tv_nsec - t0.tv_nsec);
}

void on_signal(int sig) {
  // The same signal again within half a second is the same request delivered
  // twice (GNU timeout and schedulers signal the process and its group).
  if (pending == sig && seconds_since(first_at) < 0.5) return;
  if (pending != 0) {  // the second signal: stop now, as the default action would
    const char msg[] = "\nmfsd: second signal, stopping at once\n";
    (void)!::write(2, msg, sizeof msg - 1);
    ::signal(sig, SIG_DFL);
    ::raise(sig);
    return;
  }
  pending = sig;
  clock_gettime(CLOCK_MONOTONIC, &first_at);
  const char msg[] =
      "\nmfsd: interrupted: finishing the step, then writing a checkpoint and a last snapshot (signal again to stop "
      "at once)\n";
  (void)!::write(2, msg, sizeof msg - 1);
}

}  // namespace

InterruptHandling::InterruptHandling() {
  pending = 0;
  struct sigaction sa {};
  sa.sa_handler = on_signal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESTART;
  sigaction(SIGINT, &sa, &previous_int);
  sigaction(SIGTERM, &sa, &previous_term);
}

InterruptHandling::~InterruptHandling() {
  sigaction(SIGINT, &previous_int, nullptr);
  sigaction(SIGTERM, &previous_term, nullptr);
}

int interrupt_signal() { return int(pending); }
void request_interrupt(int signal) { pending = signal; }
void clear_interrupt() { pending = 0; }

}  // namespace mfsd
