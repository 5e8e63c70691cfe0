// stereo_sim interrupted (Ctrl-C, kill): the progress line it was rewriting in place
// ("\rsimulated frame i/n") is ended, so the shell's prompt and the signal's message do
// not land in the middle of it. The temporaries are removed by toolio's
// sm_signal_cleanup (RemoveOnSignal), which runs this handler after its own.
#pragma once

namespace sm::simapp {

// Installs the SIGINT / SIGTERM handler that ends an open progress line and then ends
// the process with the signal. Call it before registering a RemoveOnSignal, so that
// that handler runs first and chains to this one.
void end_progress_line_on_signal();

// Whether a progress line is open (printed without its newline yet).
void set_progress_line_open(bool open);

}  // namespace sm::simapp
