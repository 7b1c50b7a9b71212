#include "app/interrupt.h"

#include <unistd.h>

#include "app/exit_codes.h"

namespace ps {

namespace {

std::atomic<bool> gInterrupt{false};

extern "C" void onInterrupt(int) {
    if (gInterrupt.exchange(true)) _exit(kExitInterrupted);
}

}  // namespace

InterruptHandlers::InterruptHandlers(std::initializer_list<int> signals) {
    gInterrupt = false;
    struct sigaction action {};
    action.sa_handler = onInterrupt;
    action.sa_flags = SA_RESTART;  // as signal() installs them: interrupted reads and writes resume
    sigemptyset(&action.sa_mask);
    for (int s : signals) {
        struct sigaction old {};
        if (sigaction(s, &action, &old) == 0) previous_.push_back({s, old});
    }
}

InterruptHandlers::~InterruptHandlers() {
    for (const auto& [s, old] : previous_) sigaction(s, &old, nullptr);
}

const std::atomic<bool>* InterruptHandlers::flag() { return &gInterrupt; }

void InterruptHandlers::request() { gInterrupt = true; }

}  // namespace ps
