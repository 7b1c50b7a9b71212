// AnimatedTransform with pbrt-v4's semantics: keyframes clamp outside their times, translation
// and the symmetric scale are interpolated linearly, the rotation by slerp.
#include <gtest/gtest.h>

#include <cmath>

#include "math/animated_transform.h"

using namespace ps;

namespace {
void expectNear(Vec3 a, Vec3 b, float tol = 1e-5f) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}
}  // namespace

TEST(AnimatedTransform, InterpolatesTranslationRotationAndScale) {
    // Start: translate (1,0,0); end: translate (3,0,0) rotate 90 about z, scale 2 4 1.
    Transform start = Transform::translate({1, 0, 0});
    Transform end = Transform::translate({3, 0, 0}) * Transform::rotate(90, {0, 0, 1}) * Transform::scale({2, 4, 1});
    AnimatedTransform a(start, 1, end, 3);
    ASSERT_TRUE(a.isAnimated());
    // Clamped outside [1, 3].
    expectNear(a.interpolate(0).point({1, 0, 0}), {2, 0, 0});
    expectNear(a.interpolate(5).point({1, 0, 0}), end.point({1, 0, 0}));
    // Halfway: translation (2,0,0), rotation 45 degrees (slerp), scale (1.5, 2.5, 1).
    Transform mid = a.interpolate(2);
    Transform expected = Transform::translate({2, 0, 0}) * Transform::rotate(45, {0, 0, 1}) * Transform::scale({1.5f, 2.5f, 1});
    for (Vec3 p : {Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1), Vec3(1, 2, 3)}) expectNear(mid.point(p), expected.point(p));
    // A quarter of the way: 22.5 degrees, a constant rate (a matrix lerp would give 18.4).
    Vec3 x = a.interpolate(1.5f).vector({1, 0, 0});
    EXPECT_NEAR(std::atan2(x.y, x.x) * 180 / M_PI, 22.5, 1e-3);
    EXPECT_FALSE(AnimatedTransform(start, 0, start, 1).isAnimated());
}
