#include "math/transform.h"

#include <cmath>
#include <limits>
#include <utility>

namespace ps {

Matrix4 Matrix4::fromRowMajor(const float v[16]) {
    Matrix4 r;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) r.m[i][j] = v[i * 4 + j];
    return r;
}

bool Matrix4::isIdentity() const { return *this == Matrix4(); }

bool Matrix4::operator==(const Matrix4& o) const {
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
            if (m[i][j] != o.m[i][j]) return false;
    return true;
}

bool Matrix4::isFinite() const {
    for (auto& row : m)
        for (float v : row)
            if (!std::isfinite(v)) return false;
    return true;
}

Matrix4 Matrix4::transposed() const {
    Matrix4 r;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) r.m[i][j] = m[j][i];
    return r;
}

Matrix4 operator*(const Matrix4& a, const Matrix4& b) {
    Matrix4 r;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
            double s = 0;
            for (int k = 0; k < 4; ++k) s += double(a.m[i][k]) * b.m[k][j];
            r.m[i][j] = float(s);
        }
    return r;
}

// Gauss-Jordan elimination with partial pivoting, in double precision.
std::optional<Matrix4> Matrix4::inverse() const {
    if (!isFinite()) return std::nullopt;
    double a[4][8];
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
            a[i][j] = m[i][j];
            a[i][j + 4] = (i == j) ? 1.0 : 0.0;
        }
    for (int c = 0; c < 4; ++c) {
        int piv = c;
        for (int r = c + 1; r < 4; ++r)
            if (std::fabs(a[r][c]) > std::fabs(a[piv][c])) piv = r;
        if (std::fabs(a[piv][c]) < 1e-12) return std::nullopt;
        if (piv != c)
            for (int j = 0; j < 8; ++j) std::swap(a[c][j], a[piv][j]);
        double inv = 1.0 / a[c][c];
        for (int j = 0; j < 8; ++j) a[c][j] *= inv;
        for (int r = 0; r < 4; ++r) {
            if (r == c) continue;
            double f = a[r][c];
            if (f != 0)
                for (int j = 0; j < 8; ++j) a[r][j] -= f * a[c][j];
        }
    }
    Matrix4 r;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) r.m[i][j] = float(a[i][j + 4]);
    if (!r.isFinite()) return std::nullopt;
    return r;
}

std::optional<Transform> Transform::fromMatrix(const Matrix4& m) {
    auto inv = m.inverse();
    if (!inv) return std::nullopt;
    return Transform(m, *inv);
}

Transform Transform::fromMatrixOrSingular(const Matrix4& m) {
    if (auto inv = m.inverse()) return Transform(m, *inv);
    Matrix4 nan;
    for (auto& row : nan.m)
        for (float& v : row) v = std::numeric_limits<float>::quiet_NaN();
    return Transform(m, nan);
}

Transform Transform::translate(Vec3 d) {
    Matrix4 m, inv;
    m.m[0][3] = d.x; m.m[1][3] = d.y; m.m[2][3] = d.z;
    inv.m[0][3] = -d.x; inv.m[1][3] = -d.y; inv.m[2][3] = -d.z;
    return Transform(m, inv);
}

Transform Transform::scale(Vec3 s) {
    Matrix4 m, inv;
    m.m[0][0] = s.x; m.m[1][1] = s.y; m.m[2][2] = s.z;
    inv.m[0][0] = 1 / s.x; inv.m[1][1] = 1 / s.y; inv.m[2][2] = 1 / s.z;
    return Transform(m, inv);
}

Transform Transform::rotate(float degrees, Vec3 axis) {
    Vec3 a = normalize(axis);
    float s = std::sin(radians(degrees)), c = std::cos(radians(degrees));
    Matrix4 m;
    m.m[0][0] = a.x * a.x + (1 - a.x * a.x) * c;
    m.m[0][1] = a.x * a.y * (1 - c) - a.z * s;
    m.m[0][2] = a.x * a.z * (1 - c) + a.y * s;
    m.m[1][0] = a.x * a.y * (1 - c) + a.z * s;
    m.m[1][1] = a.y * a.y + (1 - a.y * a.y) * c;
    m.m[1][2] = a.y * a.z * (1 - c) - a.x * s;
    m.m[2][0] = a.x * a.z * (1 - c) - a.y * s;
    m.m[2][1] = a.y * a.z * (1 - c) + a.x * s;
    m.m[2][2] = a.z * a.z + (1 - a.z * a.z) * c;
    return Transform(m, m.transposed());
}

std::optional<Transform> Transform::lookAt(Vec3 eye, Vec3 target, Vec3 up) {
    Vec3 d = target - eye;
    if (!(lengthSquared(d) > 0) || !(lengthSquared(up) > 0)) return std::nullopt;
    Vec3 dir = normalize(d);
    Vec3 rc = cross(normalize(up), dir);
    if (!(lengthSquared(rc) > 0)) return std::nullopt;
    Vec3 right = normalize(rc);
    Vec3 newUp = cross(dir, right);
    Matrix4 worldFromCamera;
    for (int i = 0; i < 3; ++i) {
        worldFromCamera.m[i][0] = right[i];
        worldFromCamera.m[i][1] = newUp[i];
        worldFromCamera.m[i][2] = dir[i];
        worldFromCamera.m[i][3] = eye[i];
    }
    return fromMatrix(worldFromCamera);
}

double Transform::linearDeterminant() const {
    const auto& a = m_.m;
    return a[0][0] * (double(a[1][1]) * a[2][2] - double(a[1][2]) * a[2][1]) -
           a[0][1] * (double(a[1][0]) * a[2][2] - double(a[1][2]) * a[2][0]) +
           a[0][2] * (double(a[1][0]) * a[2][1] - double(a[1][1]) * a[2][0]);
}

Vec3 Transform::normal(Vec3 n) const {
    const auto& a = inv_.m;
    return {a[0][0] * n.x + a[1][0] * n.y + a[2][0] * n.z,
            a[0][1] * n.x + a[1][1] * n.y + a[2][1] * n.z,
            a[0][2] * n.x + a[1][2] * n.y + a[2][2] * n.z};
}

}  // namespace ps
