#include "util/error.h"

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <mutex>
#include <set>

#include "util/input_files.h"

namespace ps {

namespace {
std::mutex gMutex;
std::set<std::string> gSeen;
std::vector<std::string> gInOrder;
std::atomic<int> gCount{0};
std::atomic<bool> gQuiet{false};
// HeldWarnings: the messages waiting, with their places (file empty: none).
bool gHolding = false;
struct Held {
    SourceLoc loc;
    std::string text;
};
std::vector<Held> gHeld;

void give(const std::string& msg, const SourceLoc* loc) {
    std::lock_guard<std::mutex> lock(gMutex);
    if (!gSeen.insert(msg).second) return;  // once per distinct message
    gInOrder.push_back(msg);
    ++gCount;
    if (gQuiet) return;
    if (gHolding) gHeld.push_back({loc ? *loc : SourceLoc{}, msg});
    else std::fprintf(stderr, "warning: %s\n", printableMessage(msg).c_str());
}
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

void warning(const std::string& msg) { give(msg, nullptr); }

void warning(const SourceLoc& loc, const std::string& msg) { give(loc.str() + ": " + msg, &loc); }

HeldWarnings::HeldWarnings() {
    std::lock_guard<std::mutex> lock(gMutex);
    gHolding = true;
}

HeldWarnings::~HeldWarnings() {
    const std::vector<std::string> files = inputFiles();
    std::lock_guard<std::mutex> lock(gMutex);
    auto fileRank = [&](const Held& h) {
        if (h.loc.file.empty()) return files.size() + 1;  // no place: after every file
        const auto it = std::find(files.begin(), files.end(), h.loc.file);
        return it == files.end() ? files.size() : size_t(it - files.begin());
    };
    std::stable_sort(gHeld.begin(), gHeld.end(), [&](const Held& a, const Held& b) {
        const size_t fa = fileRank(a), fb = fileRank(b);
        if (fa != fb) return fa < fb;
        if (a.loc.file.empty()) return false;  // keep the given order
        return a.loc.line != b.loc.line ? a.loc.line < b.loc.line : a.loc.column < b.loc.column;
    });
    for (const Held& h : gHeld) std::fprintf(stderr, "warning: %s\n", printableMessage(h.text).c_str());
    gHeld.clear();
    gHolding = false;
}

int warningCount() { return gCount; }
std::vector<std::string> warningMessages() {
    std::lock_guard<std::mutex> lock(gMutex);
    return gInOrder;
}
void setWarningsQuiet(bool quiet) { gQuiet = quiet; }

}  // namespace ps
