// The memory limit: before a buffer sized from the user's input (film, image, mesh) is
// allocated, its size is checked against one process-wide limit, so a huge or corrupt
// input ends in an error that says how much it needs instead of in bad_alloc or the OOM killer.
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "util/error.h"

namespace ps {

// The limit in bytes; by default 80% of physical memory (16 GiB where that is unknown).
// Safe to read from any thread.
uint64_t memoryLimit();
void setMemoryLimit(uint64_t bytes);

// Sets the limit for a scope and restores the one before (tests, the fuzz harness).
class ScopedMemoryLimit {
public:
    explicit ScopedMemoryLimit(uint64_t bytes) : saved_(memoryLimit()) { setMemoryLimit(bytes); }
    ~ScopedMemoryLimit() { setMemoryLimit(saved_); }
    ScopedMemoryLimit(const ScopedMemoryLimit&) = delete;
    ScopedMemoryLimit& operator=(const ScopedMemoryLimit&) = delete;
    uint64_t saved() const { return saved_; }

private:
    uint64_t saved_;
};

// "512 B", "3.2 MiB", "44.7 TiB" (binary units, one decimal).
std::string formatBytes(uint64_t bytes);

// "123456", "512K", "512M", "8G", "1.5G", "2T": a byte count with an optional binary unit
// (K M G T P, optionally followed by "B" or "iB", any case). Nothing for zero, negative,
// malformed or overflowing sizes.
std::optional<uint64_t> parseByteSize(std::string_view text);

// Throws InputError("<what> needs <bytes> of memory, more than the limit of <limit> (raise it
// with --max-memory)") if bytes exceeds the limit. A double, so that callers can multiply
// header fields without overflow; NaN fails too. The second form puts the message after a
// file:line:column, as InputError(loc, ...) does.
void requireMemory(const std::string& what, double bytes);
void requireMemory(const SourceLoc& loc, const std::string& what, double bytes);

}  // namespace ps
