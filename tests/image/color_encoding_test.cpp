#include <gtest/gtest.h>

#include <cmath>

#include "image/image.h"

using namespace ps;

// Values from the piecewise definition in IEC 61966-2-1.
TEST(ColorEncoding, KnownPoints) {
    EXPECT_EQ(srgbToLinear(0.0f), 0.0f);
    EXPECT_EQ(linearToSrgb(0.0f), 0.0f);
    EXPECT_FLOAT_EQ(srgbToLinear(1.0f), 1.0f);
    EXPECT_FLOAT_EQ(linearToSrgb(1.0f), 1.0f);
    EXPECT_NEAR(srgbToLinear(0.5f), 0.2140411f, 1e-7f);
    EXPECT_NEAR(linearToSrgb(0.18f), 0.4613561f, 1e-6f);
    EXPECT_NEAR(srgbToLinear(128 / 255.0f), 0.2158605f, 1e-7f);
    // Linear segment: slope 12.92 below the breakpoint.
    EXPECT_FLOAT_EQ(srgbToLinear(0.02f), 0.02f / 12.92f);
    EXPECT_FLOAT_EQ(linearToSrgb(0.001f), 0.01292f);
    EXPECT_NEAR(srgbToLinear(0.04045f), 0.0031308f, 1e-8f);
}

TEST(ColorEncoding, MonotonicAndMutuallyInverse) {
    float prevLin = -1, prevSrgb = -1;
    for (int i = 0; i <= 100000; ++i) {
        float v = i / 100000.0f;
        float lin = srgbToLinear(v), enc = linearToSrgb(v);
        EXPECT_GE(lin, prevLin) << v;
        EXPECT_GE(enc, prevSrgb) << v;
        prevLin = lin;
        prevSrgb = enc;
        EXPECT_NEAR(linearToSrgb(lin), v, 2e-6f) << v;
    }
    // Consecutive floats around both breakpoints, where the two segments meet.
    for (float mid : {0.04045f, 0.0031308f}) {
        float v = mid;
        for (int i = 0; i < 64; ++i) v = std::nextafter(v, 0.0f);
        float a = srgbToLinear(v), b = linearToSrgb(v);
        for (int i = 0; i < 128; ++i) {
            float next = std::nextafter(v, 1.0f);
            EXPECT_GE(srgbToLinear(next), a);
            EXPECT_GE(linearToSrgb(next), b);
            a = srgbToLinear(next);
            b = linearToSrgb(next);
            v = next;
        }
    }
}
