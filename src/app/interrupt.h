// Ctrl-C (and SIGTERM for the commands) during a long computation: the first signal asks it to
// stop at its next boundary and keep what it has; the second ends the process at once (exit
// status 130). Shared by `render`, `verify` and the Python module's render.
#pragma once
#include <atomic>
#include <csignal>
#include <initializer_list>
#include <vector>

namespace ps {

class InterruptHandlers {
public:
    // Clears the flag and installs the handlers for these signals; the destructor puts back
    // the handlers that were there before (the Python interpreter's own, for the module).
    explicit InterruptHandlers(std::initializer_list<int> signals);
    ~InterruptHandlers();
    InterruptHandlers(const InterruptHandlers&) = delete;
    InterruptHandlers& operator=(const InterruptHandlers&) = delete;

    // Set by the first signal: what RenderOptions::cancel points at.
    static const std::atomic<bool>* flag();
    static bool interrupted() { return flag()->load(); }
    // What the first signal does, asked for by the program (a failed progress callback).
    static void request();

private:
    std::vector<std::pair<int, struct sigaction>> previous_;
};

}  // namespace ps
