#include "run/interrupt.hpp"

#include <csignal>

#include "io/temporary_files.hpp"

namespace periadapt {

namespace {

volatile std::sig_atomic_t g_signal = 0;

extern "C" void on_signal(int sig) {
  if (g_signal != 0) {
    // Ends at once: a write in progress leaves its final name as it was, and no temporary.
    remove_temporary_files_now();
    std::signal(sig, SIG_DFL);
    std::raise(sig);
    return;
  }
  g_signal = sig;
}

}  // namespace

void install_interrupt_handlers() {
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
}

int interrupt_signal() { return g_signal; }

}  // namespace periadapt
