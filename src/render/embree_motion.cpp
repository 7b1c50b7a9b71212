#include "render/embree_motion.h"

#include <algorithm>
#include <cmath>

namespace ps {

namespace {

struct M3 {
    double a[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
};

M3 mul(const M3& x, const M3& y) {
    M3 r;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            double s = 0;
            for (int k = 0; k < 3; ++k) s += x.a[i][k] * y.a[k][j];
            r.a[i][j] = s;
        }
    return r;
}

M3 transpose(const M3& x) {
    M3 r;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) r.a[i][j] = x.a[j][i];
    return r;
}

M3 fromMatrix(const Matrix4& m) {
    M3 r;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) r.a[i][j] = m.m[i][j];
    return r;
}

Matrix4 toMatrix(const M3& x) {
    Matrix4 r;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) r.m[i][j] = float(x.a[i][j]);
    return r;
}

double lowerMagnitude(const M3& x) { return std::max({std::fabs(x.a[1][0]), std::fabs(x.a[2][0]), std::fabs(x.a[2][1])}); }

double maxMagnitude(const M3& x) {
    double m = 0;
    for (auto& row : x.a)
        for (double v : row) m = std::max(m, std::fabs(v));
    return m;
}

// Inverse by cofactors; the caller's matrices are invertible (non-singular CTMs).
M3 inverse(const M3& x) {
    const auto& a = x.a;
    double det = a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
                 a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
    M3 r;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            int i1 = (j + 1) % 3, i2 = (j + 2) % 3, j1 = (i + 1) % 3, j2 = (i + 2) % 3;
            r.a[i][j] = (a[i1][j1] * a[i2][j2] - a[i1][j2] * a[i2][j1]) / det;
        }
    return r;
}

// A = Q R by modified Gram-Schmidt on the columns.
void qr(const M3& A, M3* Q, M3* R) {
    *R = M3();
    for (int j = 0; j < 3; ++j) {
        double v[3] = {A.a[0][j], A.a[1][j], A.a[2][j]};
        for (int k = 0; k < j; ++k) {
            double d = Q->a[0][k] * v[0] + Q->a[1][k] * v[1] + Q->a[2][k] * v[2];
            R->a[k][j] = d;
            for (int i = 0; i < 3; ++i) v[i] -= d * Q->a[i][k];
        }
        double n = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
        R->a[j][j] = n;
        for (int k = 0; k < j; ++k) R->a[j][k] = 0;
        for (int i = 0; i < 3; ++i) Q->a[i][j] = n > 0 ? v[i] / n : 0.0;
    }
}

// Real Schur form A = Q U Q^T (U upper triangular) by unshifted QR iteration; A's
// eigenvalues are real and positive here. Returns whether U's lower part vanished.
bool schur(const M3& A, M3* Q, M3* U) {
    M3 acc, cur = A;
    const double tolerance = 1e-9 * maxMagnitude(A);
    for (int it = 0; it < 2000 && lowerMagnitude(cur) > tolerance; ++it) {
        M3 q, r;
        qr(cur, &q, &r);
        cur = mul(r, q);
        acc = mul(acc, q);
    }
    bool converged = lowerMagnitude(cur) <= 1e-6 * maxMagnitude(A);
    // A proper rotation: flipping a basis vector keeps U upper triangular.
    const auto& a = acc.a;
    double det = a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
                 a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
    if (det < 0)
        for (int i = 0; i < 3; ++i) acc.a[i][2] = -acc.a[i][2];
    *Q = acc;
    *U = mul(transpose(acc), mul(A, acc));
    U->a[1][0] = U->a[2][0] = U->a[2][1] = 0;
    return converged;
}

void fillStep(RTCQuaternionDecomposition& qd, Vec3 t, const Quaternion& q, const M3& u) {
    rtcInitQuaternionDecomposition(&qd);
    rtcQuaternionDecompositionSetScale(&qd, float(u.a[0][0]), float(u.a[1][1]), float(u.a[2][2]));
    rtcQuaternionDecompositionSetSkew(&qd, float(u.a[0][1]), float(u.a[0][2]), float(u.a[1][2]));
    rtcQuaternionDecompositionSetQuaternion(&qd, q.w, q.v.x, q.v.y, q.v.z);
    rtcQuaternionDecompositionSetTranslation(&qd, t.x, t.y, t.z);
}

}  // namespace

EmbreeMotion embreeMotion(const AnimatedTransform& motion) {
    EmbreeMotion em;
    M3 s0 = fromMatrix(motion.scale(0)), s1 = fromMatrix(motion.scale(1));
    const double scale = std::max(maxMagnitude(s0), maxMagnitude(s1));
    Quaternion q0 = motion.rotation(0), q1 = motion.rotation(1);
    M3 u0 = s0, u1 = s1;
    if (lowerMagnitude(s0) > 1e-7 * scale || lowerMagnitude(s1) > 1e-7 * scale) {
        M3 Q, U;
        em.exact = schur(mul(s1, inverse(s0)), &Q, &U);
        u0 = M3();
        u1 = U;
        Matrix4 q = toMatrix(Q);
        q0 = quaternionOf(rotationMatrix(q0) * q);
        q1 = quaternionOf(rotationMatrix(q1) * q);
        if (dot(q0, q1) < 0) q1 = {-q1.v, -q1.w};
        em.prototypeFromObject = Transform::fromMatrixOrSingular(toMatrix(mul(transpose(Q), s0)));
    }
    fillStep(em.steps[0], motion.translation(0), q0, u0);
    fillStep(em.steps[1], motion.translation(1), q1, u1);
    return em;
}

}  // namespace ps
