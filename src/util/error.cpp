#include "util/error.h"

#include <atomic>
#include <cstdio>
#include <mutex>
#include <set>

namespace ps {

namespace {
std::mutex gMutex;
std::set<std::string> gSeen;
std::vector<std::string> gInOrder;
std::atomic<int> gCount{0};
std::atomic<bool> gQuiet{false};
}  // namespace

namespace {
// Printable ASCII as is, other bytes as \xNN. A quoted token also escapes backslashes and
// line breaks; a whole message keeps its own line breaks.
void appendEscaped(std::string& out, std::string_view text, bool quoted) {
    static const char kHex[] = "0123456789abcdef";
    for (unsigned char c : text) {
        if (c == '\\' && quoted) {
            out += "\\\\";
        } else if ((c >= 0x20 && c < 0x7f) || (!quoted && (c == '\n' || c == '\t'))) {
            out += char(c);
        } else {
            out += "\\x";
            out += kHex[c >> 4];
            out += kHex[c & 15];
        }
    }
}
}  // namespace

std::string quoteForMessage(std::string_view text, size_t maxChars) {
    std::string out = "\"";
    appendEscaped(out, text.substr(0, maxChars), true);
    if (text.size() > maxChars) out += "...";
    return out + "\"";
}

std::string printableMessage(std::string_view text) {
    std::string out;
    appendEscaped(out, text, false);
    return out;
}

void warning(const std::string& msg) {
    std::lock_guard<std::mutex> lock(gMutex);
    if (!gSeen.insert(msg).second) return;  // once per distinct message
    gInOrder.push_back(msg);
    ++gCount;
    if (!gQuiet) std::fprintf(stderr, "warning: %s\n", printableMessage(msg).c_str());
}

void warning(const SourceLoc& loc, const std::string& msg) { warning(loc.str() + ": " + msg); }

int warningCount() { return gCount; }
std::vector<std::string> warningMessages() {
    std::lock_guard<std::mutex> lock(gMutex);
    return gInOrder;
}
void setWarningsQuiet(bool quiet) { gQuiet = quiet; }

}  // namespace ps
