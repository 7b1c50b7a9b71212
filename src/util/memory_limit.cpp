#include "util/memory_limit.h"

#include <unistd.h>

#include <atomic>
#include <cmath>
#include <cstdio>

namespace ps {

namespace {

constexpr uint64_t kGiB = uint64_t(1) << 30;

// 80% leaves room for what no check counts (the BVH, the program, the rest of the system).
uint64_t defaultLimit() {
    long pages = sysconf(_SC_PHYS_PAGES), pageSize = sysconf(_SC_PAGESIZE);
    if (pages <= 0 || pageSize <= 0) return 16 * kGiB;
    return uint64_t(0.8 * double(pages) * double(pageSize));
}

std::atomic<uint64_t>& limit() {
    static std::atomic<uint64_t> value{defaultLimit()};
    return value;
}

// A double, because estimates can exceed what uint64_t holds.
std::string formatAmount(double bytes) {
    char buf[48];
    if (bytes < 1023.5) {
        std::snprintf(buf, sizeof buf, "%.0f B", bytes);
        return buf;
    }
    static const char* const kUnits[] = {"KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
    double v = bytes / 1024;
    int unit = 0;
    while (v >= 1023.95 && unit < 5) {  // 1023.95 would print as "1024.0"
        v /= 1024;
        ++unit;
    }
    std::snprintf(buf, sizeof buf, "%.1f %s", v, kUnits[unit]);
    return buf;
}

bool isDigit(char c) { return c >= '0' && c <= '9'; }
char lower(char c) { return c >= 'A' && c <= 'Z' ? char(c - 'A' + 'a') : c; }

std::string exceeded(const std::string& what, double bytes) {
    return what + " needs " + formatAmount(bytes) + " of memory, more than the limit of " +
           formatAmount(double(limit().load(std::memory_order_relaxed))) + " (raise it with --max-memory)";
}

}  // namespace

uint64_t memoryLimit() { return limit().load(std::memory_order_relaxed); }
void setMemoryLimit(uint64_t bytes) { limit().store(bytes, std::memory_order_relaxed); }

std::string formatBytes(uint64_t bytes) { return formatAmount(double(bytes)); }

std::optional<uint64_t> parseByteSize(std::string_view s) {
    size_t i = 0;
    uint64_t whole = 0;
    bool digits = false;
    for (; i < s.size() && isDigit(s[i]); ++i, digits = true) {
        uint64_t d = uint64_t(s[i] - '0');
        if (whole > (UINT64_MAX - d) / 10) return std::nullopt;
        whole = whole * 10 + d;
    }
    bool point = i < s.size() && s[i] == '.';
    double fraction = 0;
    if (point)
        for (double scale = 0.1; ++i < s.size() && isDigit(s[i]); scale /= 10, digits = true)
            fraction += double(s[i] - '0') * scale;
    if (!digits) return std::nullopt;
    int shift = 0;  // log2 of the unit
    static constexpr std::string_view kUnits = "kmgtp";
    if (size_t u = i < s.size() ? kUnits.find(lower(s[i])) : std::string_view::npos; u != std::string_view::npos) {
        shift = 10 * int(u + 1);
        if (++i < s.size() && lower(s[i]) == 'i') {
            if (++i == s.size() || lower(s[i]) != 'b') return std::nullopt;
        }
    }
    if (i < s.size() && lower(s[i]) == 'b') ++i;
    if (i != s.size() || (point && shift == 0)) return std::nullopt;  // no fractions of a byte
    if (whole > (UINT64_MAX >> shift)) return std::nullopt;
    uint64_t bytes = whole << shift;
    uint64_t part = uint64_t(fraction * double(uint64_t(1) << shift));  // below one unit
    if (bytes > UINT64_MAX - part) return std::nullopt;
    bytes += part;
    if (bytes == 0) return std::nullopt;
    return bytes;
}

void requireMemory(const std::string& what, double bytes) {
    if (!(bytes <= double(memoryLimit()))) throw InputError(exceeded(what, bytes));
}

void requireMemory(const SourceLoc& loc, const std::string& what, double bytes) {
    if (!(bytes <= double(memoryLimit()))) throw InputError(loc, exceeded(what, bytes));
}

}  // namespace ps
