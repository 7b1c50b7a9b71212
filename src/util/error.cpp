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

std::string quoteForMessage(std::string_view text, size_t maxChars) {
    std::string out = "\"";
    for (size_t i = 0; i < text.size() && i < maxChars; ++i) {
        unsigned char c = static_cast<unsigned char>(text[i]);
        if (c == '\\') {
            out += '\\';
            out += char(c);
        } else if (c >= 0x20 && c < 0x7f) {
            out += char(c);
        } else {
            static const char kHex[] = "0123456789abcdef";
            out += "\\x";
            out += kHex[c >> 4];
            out += kHex[c & 15];
        }
    }
    if (text.size() > maxChars) out += "...";
    return out + "\"";
}

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
