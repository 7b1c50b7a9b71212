#include <gtest/gtest.h>

#include "math/transform.h"

using namespace ps;

static void expectNear(Vec3 a, Vec3 b, float eps = 1e-5f) {
    EXPECT_NEAR(a.x, b.x, eps);
    EXPECT_NEAR(a.y, b.y, eps);
    EXPECT_NEAR(a.z, b.z, eps);
}

TEST(Transform, TranslateScaleRotate) {
    expectNear(Transform::translate({1, 2, 3}).point({1, 1, 1}), {2, 3, 4});
    expectNear(Transform::translate({1, 2, 3}).vector({1, 1, 1}), {1, 1, 1});
    expectNear(Transform::scale({2, 3, 4}).point({1, 1, 1}), {2, 3, 4});
    expectNear(Transform::rotate(90, {0, 0, 1}).point({1, 0, 0}), {0, 1, 0});
    expectNear(Transform::rotate(90, {1, 0, 0}).point({0, 1, 0}), {0, 0, 1});
}

TEST(Transform, InverseAndComposition) {
    Transform t = Transform::translate({1, -2, 3}) * Transform::rotate(33, {1, 2, 3}) * Transform::scale({2, 0.5f, 3});
    Vec3 p(0.3f, -1.7f, 2.2f);
    expectNear(t.inverse().point(t.point(p)), p, 1e-4f);
    auto inv = t.matrix().inverse();
    ASSERT_TRUE(inv.has_value());
    Matrix4 id = t.matrix() * *inv;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) EXPECT_NEAR(id.m[i][j], i == j ? 1.0f : 0.0f, 1e-5f);
}

TEST(Transform, SingularAndNonFiniteAreRejected) {
    Matrix4 m;
    m.m[1][1] = 0;
    EXPECT_FALSE(Transform::fromMatrix(m).has_value());
    m.m[1][1] = std::numeric_limits<float>::quiet_NaN();
    EXPECT_FALSE(Transform::fromMatrix(m).has_value());
}

TEST(Transform, NormalsStayPerpendicular) {
    Transform t = Transform::scale({1, 4, 1}) * Transform::rotate(20, {0, 0, 1});
    Vec3 tangent(1, 1, 0), normal(1, -1, 0);
    EXPECT_NEAR(dot(t.vector(tangent), t.normal(normal)), 0.0f, 1e-5f);
}

TEST(Transform, Handedness) {
    EXPECT_TRUE(Transform::scale({-1, 1, 1}).swapsHandedness());
    EXPECT_FALSE(Transform::scale({-1, -1, 1}).swapsHandedness());
    EXPECT_FALSE(Transform::rotate(70, {1, 1, 0}).swapsHandedness());
}

// pbrt's LookAt: camera +z looks at the target, +y is up, and +x (image right) is
// up x dir, so looking down -z with +y up, world +x appears on the image left.
TEST(Transform, LookAtFollowsPbrtConvention) {
    auto t = Transform::lookAt({0, 0, 0}, {0, 0, -1}, {0, 1, 0});
    ASSERT_TRUE(t.has_value());
    expectNear(t->vector({0, 0, 1}), {0, 0, -1});
    expectNear(t->vector({0, 1, 0}), {0, 1, 0});
    expectNear(t->vector({1, 0, 0}), {-1, 0, 0});
    EXPECT_FALSE(Transform::lookAt({0, 0, 0}, {0, 0, 0}, {0, 1, 0}).has_value());
    EXPECT_FALSE(Transform::lookAt({0, 0, 0}, {0, 1, 0}, {0, 1, 0}).has_value());
}
