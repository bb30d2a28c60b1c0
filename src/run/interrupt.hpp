#pragma once
// SIGINT / SIGTERM during a run: the first one asks the run to stop after the current step and
// write its outputs and summary (status "interrupted"); a second one ends the process at once.

namespace periadapt {

void install_interrupt_handlers();
// The signal that asked the run to stop, 0 while none did.
int interrupt_signal();

}  // namespace periadapt
