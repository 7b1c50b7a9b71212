#include "util/error.h"

#include <atomic>
#include <cstdio>
#include <mutex>
#include <set>

namespace ps {

namespace {
std::mutex gMutex;
std::set<std::string> gSeen;
std::atomic<int> gCount{0};
std::atomic<bool> gQuiet{false};
}  // namespace

void warning(const std::string& msg) {
    std::lock_guard<std::mutex> lock(gMutex);
    if (!gSeen.insert(msg).second) return;  // once per distinct message
    ++gCount;
    if (!gQuiet) std::fprintf(stderr, "warning: %s\n", msg.c_str());
}

void warning(const SourceLoc& loc, const std::string& msg) { warning(loc.str() + ": " + msg); }

int warningCount() { return gCount; }
void setWarningsQuiet(bool quiet) { gQuiet = quiet; }

}  // namespace ps
