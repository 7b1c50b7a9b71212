// 3x3 matrices in double precision, for the linear algebra done once per scene (colour-space
// conversions, decompositions of animated transforms), where float would lose digits.
#pragma once
#include <array>

#include "math/transform.h"

namespace ps {

struct Matrix3 {
    double a[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};

    // The linear (upper-left 3x3) part of m, and a Matrix4 with this as its linear part.
    static Matrix3 linearPart(const Matrix4& m) {
        Matrix3 r;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) r.a[i][j] = m.m[i][j];
        return r;
    }
    Matrix4 toMatrix4() const {
        Matrix4 r;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) r.m[i][j] = float(a[i][j]);
        return r;
    }
    double determinant() const {
        return a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
               a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
    }
    Matrix3 transposed() const {
        Matrix3 r;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) r.a[i][j] = a[j][i];
        return r;
    }
    // Inverse by cofactors over the determinant; a singular matrix gives infinities or NaNs
    // (callers check the determinant where that can happen).
    Matrix3 inverse() const {
        const double det = determinant();
        Matrix3 r;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
                const int i1 = (j + 1) % 3, i2 = (j + 2) % 3, j1 = (i + 1) % 3, j2 = (i + 2) % 3;
                r.a[i][j] = (a[i1][j1] * a[i2][j2] - a[i1][j2] * a[i2][j1]) / det;
            }
        return r;
    }
    std::array<double, 3> operator*(const std::array<double, 3>& v) const {
        return {a[0][0] * v[0] + a[0][1] * v[1] + a[0][2] * v[2], a[1][0] * v[0] + a[1][1] * v[1] + a[1][2] * v[2],
                a[2][0] * v[0] + a[2][1] * v[1] + a[2][2] * v[2]};
    }
};

inline Matrix3 operator*(const Matrix3& x, const Matrix3& y) {
    Matrix3 r;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            double s = 0;
            for (int k = 0; k < 3; ++k) s += x.a[i][k] * y.a[k][j];
            r.a[i][j] = s;
        }
    return r;
}

}  // namespace ps
