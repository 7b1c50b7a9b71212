#include "math/animated_transform.h"
#include "math/matrix3.h"

#include <algorithm>
#include <cmath>

namespace ps {

namespace {

// Polar decomposition M = R S (R orthogonal, S symmetric) by the averaging iteration
// R <- (R + R^-T) / 2, stopped as pbrt-v4 stops it (row sums of changes below 1e-4, at most
// 100 steps). A reflection (det < 0) is carried by S so that R is a rotation a quaternion
// can hold.
void polarDecompose(const Matrix4& m, Matrix4* rotation, Matrix4* scale) {
    const Matrix3 M = Matrix3::linearPart(m);
    Matrix3 R = M;
    for (int count = 0; count < 100; ++count) {
        const double d = R.determinant();
        if (!(std::fabs(d) > 0) || !std::isfinite(d)) break;
        const Matrix3 Rit = R.inverse().transposed();
        double norm = 0;
        for (int i = 0; i < 3; ++i) {
            double rowChange = 0;
            for (int j = 0; j < 3; ++j) {
                double next = 0.5 * (R.a[i][j] + Rit.a[i][j]);
                rowChange += std::fabs(next - R.a[i][j]);
                R.a[i][j] = next;
            }
            norm = std::max(norm, rowChange);
        }
        if (norm <= 1e-4) break;
    }
    double sign = R.determinant() < 0 ? -1 : 1;
    *rotation = Matrix4();
    *scale = Matrix4();
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            rotation->m[i][j] = float(sign * R.a[i][j]);
            double s = 0;  // S = R^T M (R orthogonal)
            for (int k = 0; k < 3; ++k) s += R.a[k][i] * M.a[k][j];
            scale->m[i][j] = float(sign * s);
        }
}

}  // namespace

float dot(const Quaternion& a, const Quaternion& b) { return dot(a.v, b.v) + a.w * b.w; }

Quaternion slerp(float t, const Quaternion& a, const Quaternion& b) {
    float c = dot(a, b);
    Quaternion r;
    if (c > 0.9995f) {  // nearly parallel: the normalised chord is the arc to rounding
        r.v = a.v * (1 - t) + b.v * t;
        r.w = a.w * (1 - t) + b.w * t;
    } else {
        float theta = std::acos(std::clamp(c, -1.0f, 1.0f)) * t;
        Quaternion perp{b.v - a.v * c, b.w - a.w * c};  // b's part orthogonal to a
        float pn = std::sqrt(dot(perp, perp));
        r.v = a.v * std::cos(theta) + perp.v * (std::sin(theta) / pn);
        r.w = a.w * std::cos(theta) + perp.w * (std::sin(theta) / pn);
    }
    float n = std::sqrt(dot(r, r));
    return {r.v / n, r.w / n};
}

Matrix4 rotationMatrix(const Quaternion& q) {
    const float x = q.v.x, y = q.v.y, z = q.v.z, w = q.w;
    Matrix4 m;
    m.m[0][0] = 1 - 2 * (y * y + z * z);
    m.m[0][1] = 2 * (x * y - z * w);
    m.m[0][2] = 2 * (x * z + y * w);
    m.m[1][0] = 2 * (x * y + z * w);
    m.m[1][1] = 1 - 2 * (x * x + z * z);
    m.m[1][2] = 2 * (y * z - x * w);
    m.m[2][0] = 2 * (x * z - y * w);
    m.m[2][1] = 2 * (y * z + x * w);
    m.m[2][2] = 1 - 2 * (x * x + y * y);
    return m;
}

Quaternion quaternionOf(const Matrix4& r) {
    const auto& m = r.m;
    double trace = double(m[0][0]) + m[1][1] + m[2][2];
    double q[4];  // x y z w
    if (trace > 0) {
        double s = std::sqrt(trace + 1) * 2;
        q[3] = 0.25 * s;
        q[0] = (m[2][1] - m[1][2]) / s;
        q[1] = (m[0][2] - m[2][0]) / s;
        q[2] = (m[1][0] - m[0][1]) / s;
    } else {
        // The largest diagonal entry keeps the square root well away from zero.
        int i = 0;
        if (m[1][1] > m[i][i]) i = 1;
        if (m[2][2] > m[i][i]) i = 2;
        int j = (i + 1) % 3, k = (i + 2) % 3;
        double s = std::sqrt(1.0 + m[i][i] - m[j][j] - m[k][k]) * 2;
        q[i] = 0.25 * s;
        q[j] = (double(m[j][i]) + m[i][j]) / s;
        q[k] = (double(m[k][i]) + m[i][k]) / s;
        q[3] = (double(m[k][j]) - m[j][k]) / s;
    }
    double n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    return {Vec3(float(q[0] / n), float(q[1] / n), float(q[2] / n)), float(q[3] / n)};
}

AnimatedTransform::AnimatedTransform(const Transform& start, float startTime, const Transform& end, float endTime)
    : start_(start), end_(end), startTime_(startTime), endTime_(endTime), animated_(!(start == end)) {
    if (!animated_) return;
    const Transform* keys[2] = {&start_, &end_};
    for (int k = 0; k < 2; ++k) {
        const Matrix4& m = keys[k]->matrix();
        T_[k] = Vec3(m.m[0][3], m.m[1][3], m.m[2][3]);
        Matrix4 rot;
        polarDecompose(m, &rot, &S_[k]);
        R_[k] = quaternionOf(rot);
    }
    if (dot(R_[0], R_[1]) < 0) R_[1] = {-R_[1].v, -R_[1].w};  // the shorter way round
}

Transform AnimatedTransform::interpolate(float time) const {
    if (!animated_ || !(time > startTime_)) return start_;
    if (time >= endTime_) return end_;
    float dt = fraction(time);
    Matrix4 s;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) s.m[i][j] = (1 - dt) * S_[0].m[i][j] + dt * S_[1].m[i][j];
    Matrix4 m = rotationMatrix(slerp(dt, R_[0], R_[1])) * s;
    Vec3 t = T_[0] * (1 - dt) + T_[1] * dt;
    m.m[0][3] = t.x;
    m.m[1][3] = t.y;
    m.m[2][3] = t.z;
    return Transform::fromMatrixOrSingular(m);
}

}  // namespace ps
