// The rule for tests that need ../shared (tests/shared_data.h): skip when it is missing,
// except in CI (CI=true), where a missing directory must fail the test.
#include <gtest/gtest-spi.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <optional>
#include <string>

#include "shared_data.h"

using ps::test::SharedData;
using ps::test::sharedDataVerdict;

namespace {

const char* kMissing = "/nonexistent-pathspace-shared/scenes";

// Sets CI for the scope, restoring what it was.
class ScopedCi {
public:
    explicit ScopedCi(const char* value) {
        if (const char* old = std::getenv("CI")) old_ = old;
        if (value) setenv("CI", value, 1);
        else unsetenv("CI");
    }
    ~ScopedCi() {
        if (old_) setenv("CI", old_->c_str(), 1);
        else unsetenv("CI");
    }

private:
    std::optional<std::string> old_;
};

void requireMissingData() { REQUIRE_SHARED_DATA(std::string(PATHSPACE_SOURCE_DIR), kMissing); }

// The one result REQUIRE_SHARED_DATA reports for a missing path under the given CI value.
testing::TestPartResult resultOfMissingData(const char* ci) {
    ScopedCi scoped(ci);
    testing::TestPartResultArray results;
    {
        testing::ScopedFakeTestPartResultReporter reporter(testing::ScopedFakeTestPartResultReporter::INTERCEPT_ONLY_CURRENT_THREAD,
                                                           &results);
        requireMissingData();
    }
    EXPECT_EQ(results.size(), 1);
    return results.size() > 0 ? results.GetTestPartResult(0)
                               : testing::TestPartResult(testing::TestPartResult::kSuccess, "", 0, "");
}

}  // namespace

TEST(SharedData, VerdictNamesTheMissingPaths) {
    std::string missing;
    EXPECT_EQ(sharedDataVerdict({PATHSPACE_SOURCE_DIR}, "true", missing), SharedData::Present);
    EXPECT_TRUE(missing.empty());
    EXPECT_EQ(sharedDataVerdict({PATHSPACE_SOURCE_DIR, kMissing}, "true", missing), SharedData::Fail);
    EXPECT_EQ(missing, kMissing);
    for (const char* notCi : {(const char*)nullptr, "", "false", "1"}) {
        EXPECT_EQ(sharedDataVerdict({kMissing}, notCi, missing), SharedData::Skip) << (notCi ? notCi : "unset");
    }
}

TEST(SharedData, MissingDataFailsInCiAndSkipsElsewhere) {
    testing::TestPartResult ci = resultOfMissingData("true");
    EXPECT_EQ(ci.type(), testing::TestPartResult::kFatalFailure);
    EXPECT_NE(std::string(ci.message()).find(kMissing), std::string::npos) << ci.message();
    std::printf("CI=true: %s\n", ci.message());
    for (const char* notCi : {(const char*)nullptr, "false"}) {
        testing::TestPartResult local = resultOfMissingData(notCi);
        EXPECT_EQ(local.type(), testing::TestPartResult::kSkip) << (notCi ? notCi : "unset");
        EXPECT_NE(std::string(local.message()).find(kMissing), std::string::npos) << local.message();
    }
}
