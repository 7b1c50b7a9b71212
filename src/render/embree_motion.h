// An AnimatedTransform as Embree's quaternion motion blur: an instance with two time steps,
// each a translation T, a rotation quaternion R and an upper-triangular scale/shear U, which
// Embree interpolates as AnimatedTransform does (T and U linearly, R by slerp).
//
// AnimatedTransform's scale/shear S(t) = (1-t) S0 + t S1 is symmetric, not upper triangular.
// With a constant rotation Q and a constant matrix C baked into the instanced geometry,
//   R(t) S(t) = [R(t) Q] [(1-t) I + t U] [Q^T S0],   U = Q^T S1 S0^-1 Q,
// which holds exactly when U is upper triangular: Q is the real Schur basis of S1 S0^-1 (a
// product of symmetric positive-definite matrices, so its eigenvalues are real). Slerping
// R0 Q to R1 Q is slerping R0 to R1, then times Q. When S0 and S1 are already upper
// triangular (diagonal: no rotated scale), C is the identity and U0 = S0, U1 = S1.
#pragma once
#include <embree3/rtcore.h>
#include "math/animated_transform.h"

namespace ps {

struct EmbreeMotion {
    RTCQuaternionDecomposition steps[2];
    Transform prototypeFromObject;  // C: geometry is stored as C times its object-space points
    bool exact = true;              // false: the Schur basis did not converge (U kept triangular)
};

EmbreeMotion embreeMotion(const AnimatedTransform& motion);

}  // namespace ps
