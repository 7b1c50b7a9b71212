#include "render/embree_motion.h"
#include "math/matrix3.h"

#include <algorithm>
#include <cmath>

namespace ps {

namespace {

double lowerMagnitude(const Matrix3& x) { return std::max({std::fabs(x.a[1][0]), std::fabs(x.a[2][0]), std::fabs(x.a[2][1])}); }

double maxMagnitude(const Matrix3& x) {
    double m = 0;
    for (auto& row : x.a)
        for (double v : row) m = std::max(m, std::fabs(v));
    return m;
}

// A = Q R by modified Gram-Schmidt on the columns.
void qr(const Matrix3& A, Matrix3* Q, Matrix3* R) {
    *R = Matrix3();
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
bool schur(const Matrix3& A, Matrix3* Q, Matrix3* U) {
    Matrix3 acc, cur = A;
    const double tolerance = 1e-9 * maxMagnitude(A);
    for (int it = 0; it < 2000 && lowerMagnitude(cur) > tolerance; ++it) {
        Matrix3 q, r;
        qr(cur, &q, &r);
        cur = r * q;
        acc = acc * q;
    }
    bool converged = lowerMagnitude(cur) <= 1e-6 * maxMagnitude(A);
    // A proper rotation: flipping a basis vector keeps U upper triangular.
    if (acc.determinant() < 0)
        for (int i = 0; i < 3; ++i) acc.a[i][2] = -acc.a[i][2];
    *Q = acc;
    *U = acc.transposed() * (A * acc);
    U->a[1][0] = U->a[2][0] = U->a[2][1] = 0;
    return converged;
}

void fillStep(RTCQuaternionDecomposition& qd, Vec3 t, const Quaternion& q, const Matrix3& u) {
    rtcInitQuaternionDecomposition(&qd);
    rtcQuaternionDecompositionSetScale(&qd, float(u.a[0][0]), float(u.a[1][1]), float(u.a[2][2]));
    rtcQuaternionDecompositionSetSkew(&qd, float(u.a[0][1]), float(u.a[0][2]), float(u.a[1][2]));
    rtcQuaternionDecompositionSetQuaternion(&qd, q.w, q.v.x, q.v.y, q.v.z);
    rtcQuaternionDecompositionSetTranslation(&qd, t.x, t.y, t.z);
}

}  // namespace

EmbreeMotion embreeMotion(const AnimatedTransform& motion) {
    EmbreeMotion em;
    Matrix3 s0 = Matrix3::linearPart(motion.scale(0)), s1 = Matrix3::linearPart(motion.scale(1));
    const double scale = std::max(maxMagnitude(s0), maxMagnitude(s1));
    Quaternion q0 = motion.rotation(0), q1 = motion.rotation(1);
    Matrix3 u0 = s0, u1 = s1;
    if (lowerMagnitude(s0) > 1e-7 * scale || lowerMagnitude(s1) > 1e-7 * scale) {
        Matrix3 Q, U;
        em.exact = schur(s1 * s0.inverse(), &Q, &U);
        u0 = Matrix3();
        u1 = U;
        Matrix4 q = Q.toMatrix4();
        q0 = quaternionOf(rotationMatrix(q0) * q);
        q1 = quaternionOf(rotationMatrix(q1) * q);
        if (dot(q0, q1) < 0) q1 = {-q1.v, -q1.w};
        em.prototypeFromObject = Transform::fromMatrixOrSingular((Q.transposed() * s0).toMatrix4());
    }
    fillStep(em.steps[0], motion.translation(0), q0, u0);
    fillStep(em.steps[1], motion.translation(1), q1, u1);
    return em;
}

}  // namespace ps
