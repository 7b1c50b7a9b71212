// The memory limit: size parsing and formatting, and the error that names both sizes.
#include "util/memory_limit.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

using namespace ps;

namespace {

constexpr uint64_t KiB = 1024, MiB = KiB * 1024, GiB = MiB * 1024, TiB = GiB * 1024;

}  // namespace

TEST(MemoryLimit, ParsesSizesWithBinaryUnits) {
    EXPECT_EQ(parseByteSize("123456"), 123456u);
    EXPECT_EQ(parseByteSize("512K"), 512 * KiB);
    EXPECT_EQ(parseByteSize("512M"), 512 * MiB);
    EXPECT_EQ(parseByteSize("8G"), 8 * GiB);
    EXPECT_EQ(parseByteSize("1.5G"), 3 * GiB / 2);
    EXPECT_EQ(parseByteSize("2T"), 2 * TiB);
    EXPECT_EQ(parseByteSize("1P"), 1024 * TiB);
    EXPECT_EQ(parseByteSize("0.5k"), 512u);
    for (const char* s : {"8GB", "8GiB", "8gib", "8g", "8gb", "8Gb"}) EXPECT_EQ(parseByteSize(s), 8 * GiB) << s;
    EXPECT_EQ(parseByteSize("100B"), 100u);
    EXPECT_EQ(parseByteSize("18446744073709551615"), UINT64_MAX);
    EXPECT_EQ(parseByteSize("16383P"), 16383 * 1024 * TiB);
}

TEST(MemoryLimit, RejectsBadSizes) {
    for (const char* s : {"", "banana", "-1", "-1G", "+1G", "0", "0G", "0.0001K", "G", ".", "1.5", "1e9", "8 G", " 8G",
                          "8G ", "8X", "8GiBB", "8iB", "8Gi", "1.2.3G", "nan", "inf",
                          "18446744073709551616", "16384P", "99999999999999999999999G"})
        EXPECT_FALSE(parseByteSize(s).has_value()) << '"' << s << '"';
}

TEST(MemoryLimit, FormatsBytes) {
    EXPECT_EQ(formatBytes(0), "0 B");
    EXPECT_EQ(formatBytes(512), "512 B");
    EXPECT_EQ(formatBytes(1023), "1023 B");
    EXPECT_EQ(formatBytes(1024), "1.0 KiB");
    EXPECT_EQ(formatBytes(3 * MiB + MiB / 5), "3.2 MiB");
    EXPECT_EQ(formatBytes(MiB - 1), "1.0 MiB");  // not "1024.0 KiB"
    EXPECT_EQ(formatBytes(8 * GiB), "8.0 GiB");
    EXPECT_EQ(formatBytes(uint64_t(44.7 * double(TiB))), "44.7 TiB");
    EXPECT_EQ(formatBytes(UINT64_MAX), "16.0 EiB");
}

TEST(MemoryLimit, DefaultIsAFractionOfPhysicalMemory) {
    EXPECT_GE(memoryLimit(), 64 * MiB);
    ScopedMemoryLimit limit(5 * MiB);
    EXPECT_EQ(memoryLimit(), 5 * MiB);
}

TEST(MemoryLimit, RequireMemoryNamesBothSizes) {
    ScopedMemoryLimit limit(MiB);
    EXPECT_NO_THROW(requireMemory("small", double(MiB)));
    EXPECT_NO_THROW(requireMemory("nothing", 0));
    try {
        requireMemory("scene.pbrt: Film 2048x2048", 3.2 * double(MiB));
        FAIL() << "no error";
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()), "scene.pbrt: Film 2048x2048 needs 3.2 MiB of memory, more than the limit of "
                                         "1.0 MiB (raise it with --max-memory)");
    }
    // Products of header fields beyond 64 bits, and NaN, fail too.
    EXPECT_THROW(requireMemory("huge", 1e30), InputError);
    EXPECT_THROW(requireMemory("nan", std::nan("")), InputError);
    try {
        requireMemory(SourceLoc{"a.pbrt", 3, 1}, "Film 1x1", 2.0 * double(MiB));
        FAIL() << "no error";
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()), "a.pbrt:3:1: error: Film 1x1 needs 2.0 MiB of memory, more than the limit of "
                                         "1.0 MiB (raise it with --max-memory)");
    }
}
