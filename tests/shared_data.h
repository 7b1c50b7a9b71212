// Tests that read ../shared (the pbrt-v4 scenes and reference renders, PATHSPACE_SHARED_DIR)
// skip when it is missing on a developer's machine, but fail in CI (CI=true), which always
// has it: a silent skip there would hide the only comparisons with an independent renderer.
#pragma once
#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

namespace ps::test {

enum class SharedData { Present, Skip, Fail };

// Present if every path exists; else Fail when `ci` (the CI environment variable, may be
// null) is "true", Skip otherwise. `missing` lists the paths that do not exist.
inline SharedData sharedDataVerdict(const std::vector<std::filesystem::path>& paths, const char* ci,
                                    std::string& missing) {
    missing.clear();
    for (const std::filesystem::path& p : paths)
        if (!std::filesystem::exists(p)) missing += (missing.empty() ? "" : ", ") + p.string();
    if (missing.empty()) return SharedData::Present;
    return ci && std::strcmp(ci, "true") == 0 ? SharedData::Fail : SharedData::Skip;
}

}  // namespace ps::test

// In a test body, before using shared data: REQUIRE_SHARED_DATA(path, ...);
#define REQUIRE_SHARED_DATA(...)                                                                          \
    do {                                                                                                  \
        std::string psMissing_;                                                                           \
        switch (::ps::test::sharedDataVerdict({__VA_ARGS__}, std::getenv("CI"), psMissing_)) {            \
            case ::ps::test::SharedData::Present: break;                                                  \
            case ::ps::test::SharedData::Skip: GTEST_SKIP() << "shared test data missing: " << psMissing_; \
            case ::ps::test::SharedData::Fail:                                                            \
                FAIL() << "shared test data missing: " << psMissing_                                      \
                       << " (CI=true: CI must provide ../shared, the comparisons with pbrt-v4 need it)";  \
        }                                                                                                 \
    } while (0)
