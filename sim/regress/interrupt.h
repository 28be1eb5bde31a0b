#pragma once
// SIGINT / SIGTERM during a long job (regress): the first stops new work and lets the job record
// what it did not finish; the process's own handler state is restored when the guard goes.
#include <csignal>

namespace shadesim {

class InterruptGuard {
 public:
  InterruptGuard();
  ~InterruptGuard();
  InterruptGuard(const InterruptGuard&) = delete;
  InterruptGuard& operator=(const InterruptGuard&) = delete;

  // Whether SIGINT or SIGTERM arrived since the guard was made, and which (0: none).
  static bool requested();
  static int signal_number();

 private:
  struct sigaction old_int_ {
  }, old_term_{};
};

}  // namespace shadesim
