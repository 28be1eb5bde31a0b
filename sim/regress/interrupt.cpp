#include "sim/regress/interrupt.h"

namespace shadesim {
namespace {

// A signal handler can only reach state of static storage; sig_atomic_t is what it may write.
volatile std::sig_atomic_t g_interrupt_signal = 0;

extern "C" void note_interrupt(int sig) { g_interrupt_signal = sig; }

}  // namespace

InterruptGuard::InterruptGuard() {
  g_interrupt_signal = 0;
  struct sigaction sa {};
  sa.sa_handler = note_interrupt;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, &old_int_);
  sigaction(SIGTERM, &sa, &old_term_);
}

InterruptGuard::~InterruptGuard() {
  sigaction(SIGINT, &old_int_, nullptr);
  sigaction(SIGTERM, &old_term_, nullptr);
}

bool InterruptGuard::requested() { return g_interrupt_signal != 0; }
int InterruptGuard::signal_number() { return g_interrupt_signal; }

}  // namespace shadesim
