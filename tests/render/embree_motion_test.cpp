// EmbreeMotion: the two Embree time steps (T, slerped R, linear upper-triangular U) times the
// constant C baked into the geometry must equal AnimatedTransform at every time, also when
// the scale changes along rotated axes (the real Schur basis case).
#include <gtest/gtest.h>

#include <cstdio>

#include "render/embree_motion.h"

using namespace ps;

namespace {

// What Embree computes at fraction t: T(t) R(t) U(t), each step's parts interpolated.
Matrix4 embreeAt(const EmbreeMotion& em, float t) {
    const RTCQuaternionDecomposition& a = em.steps[0];
    const RTCQuaternionDecomposition& b = em.steps[1];
    auto lerp = [t](float x, float y) { return (1 - t) * x + t * y; };
    Quaternion q = slerp(t, Quaternion{{a.quaternion_i, a.quaternion_j, a.quaternion_k}, a.quaternion_r},
                         Quaternion{{b.quaternion_i, b.quaternion_j, b.quaternion_k}, b.quaternion_r});
    Matrix4 u;
    u.m[0][0] = lerp(a.scale_x, b.scale_x);
    u.m[1][1] = lerp(a.scale_y, b.scale_y);
    u.m[2][2] = lerp(a.scale_z, b.scale_z);
    u.m[0][1] = lerp(a.skew_xy, b.skew_xy);
    u.m[0][2] = lerp(a.skew_xz, b.skew_xz);
    u.m[1][2] = lerp(a.skew_yz, b.skew_yz);
    Matrix4 m = rotationMatrix(q) * u;
    m.m[0][3] = lerp(a.translation_x, b.translation_x);
    m.m[1][3] = lerp(a.translation_y, b.translation_y);
    m.m[2][3] = lerp(a.translation_z, b.translation_z);
    return m * em.prototypeFromObject.matrix();
}

double maxDifference(const AnimatedTransform& a, const EmbreeMotion& em) {
    double worst = 0;
    for (float t : {0.0f, 0.2f, 0.5f, 0.7f, 1.0f}) {
        Matrix4 e = embreeAt(em, t), p = a.interpolate(t).matrix();
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 4; ++j) worst = std::max(worst, double(std::fabs(e.m[i][j] - p.m[i][j])));
    }
    return worst;
}

}  // namespace

TEST(EmbreeMotion, StepsReproduceTheAnimatedTransform) {
    // Axis-aligned scale change with rotation: C is the identity.
    AnimatedTransform simple(Transform::translate({1, 2, 3}), 0,
                             Transform::translate({4, 0, 1}) * Transform::rotate(120, {1, 1, 0}) * Transform::scale({2, 1, 3}), 1);
    EmbreeMotion a = embreeMotion(simple);
    EXPECT_TRUE(a.prototypeFromObject.isIdentity());
    double da = maxDifference(simple, a);
    // Scale along rotated axes changing over time: S is not diagonal, C is not the identity.
    AnimatedTransform skewed(Transform::rotate(30, {0, 0, 1}) * Transform::scale({1, 3, 1}) * Transform::rotate(-30, {0, 0, 1}), 0,
                             Transform::translate({0, 1, 0}) * Transform::rotate(70, {0, 1, 0}) *
                                 Transform::scale({2, 1, 0.5f}) * Transform::rotate(50, {1, 0, 1}),
                             1);
    EmbreeMotion b = embreeMotion(skewed);
    EXPECT_TRUE(b.exact);
    EXPECT_FALSE(b.prototypeFromObject.isIdentity());
    double db = maxDifference(skewed, b);
    std::printf("  largest matrix entry difference: axis-aligned %.2e, rotated scale %.2e (tolerance 1e-4)\n", da, db);
    EXPECT_LT(da, 1e-4);
    EXPECT_LT(db, 1e-4);
}
