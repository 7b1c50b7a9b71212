// Affine/projective 4x4 transforms with their inverse, as the scene's CTM needs.
#pragma once
#include <optional>
#include "math/vec.h"

namespace ps {

struct Matrix4 {
    float m[4][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}};
    Matrix4() = default;
    static Matrix4 fromRowMajor(const float v[16]);
    bool isIdentity() const;
    Matrix4 transposed() const;
    // nullopt when singular or not finite.
    std::optional<Matrix4> inverse() const;
    bool isFinite() const;
    bool operator==(const Matrix4& o) const;
};
Matrix4 operator*(const Matrix4& a, const Matrix4& b);

class Transform {
public:
    Transform() = default;
    Transform(const Matrix4& m, const Matrix4& inv) : m_(m), inv_(inv) {}
    // nullopt when m is not invertible.
    static std::optional<Transform> fromMatrix(const Matrix4& m);
    // As pbrt-v4 builds a Transform: a singular or non-finite m gets a NaN inverse, so the
    // result is not invertible (isInvertible) and products with it stay so.
    static Transform fromMatrixOrSingular(const Matrix4& m);

    static Transform translate(Vec3 d);
    static Transform scale(Vec3 s);
    static Transform rotate(float degrees, Vec3 axis);
    // world-from-camera for a camera at eye looking at target (pbrt's LookAt, inverted).
    static std::optional<Transform> lookAt(Vec3 eye, Vec3 target, Vec3 up);

    const Matrix4& matrix() const { return m_; }
    const Matrix4& inverseMatrix() const { return inv_; }
    Transform inverse() const { return Transform(inv_, m_); }
    bool isIdentity() const { return m_.isIdentity(); }
    // Both the matrix and its inverse are finite: false after a singular or non-finite step.
    bool isInvertible() const { return m_.isFinite() && inv_.isFinite(); }
    // True when the transform flips handedness (negative determinant of the 3x3 part).
    bool swapsHandedness() const { return linearDeterminant() < 0; }
    // Determinant of the 3x3 (linear) part: how the transform scales volumes.
    double linearDeterminant() const;

    // Inline: on the per-sample paths (camera rays, instances, lens connections).
    Vec3 point(Vec3 p) const {
        const auto& a = m_.m;
        float x = a[0][0] * p.x + a[0][1] * p.y + a[0][2] * p.z + a[0][3];
        float y = a[1][0] * p.x + a[1][1] * p.y + a[1][2] * p.z + a[1][3];
        float z = a[2][0] * p.x + a[2][1] * p.y + a[2][2] * p.z + a[2][3];
        float w = a[3][0] * p.x + a[3][1] * p.y + a[3][2] * p.z + a[3][3];
        return w == 1 ? Vec3(x, y, z) : Vec3(x, y, z) / w;
    }
    Vec3 vector(Vec3 v) const {
        const auto& a = m_.m;
        return {a[0][0] * v.x + a[0][1] * v.y + a[0][2] * v.z, a[1][0] * v.x + a[1][1] * v.y + a[1][2] * v.z,
                a[2][0] * v.x + a[2][1] * v.y + a[2][2] * v.z};
    }
    // Normals transform by the inverse transpose.
    Vec3 normal(Vec3 n) const;

    Transform operator*(const Transform& o) const { return Transform(m_ * o.m_, o.inv_ * inv_); }
    bool operator==(const Transform& o) const { return m_ == o.m_; }

private:
    Matrix4 m_, inv_;
};

}  // namespace ps
