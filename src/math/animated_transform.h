// A transform moving between two keyframes, with pbrt-v4's semantics for motion blur: each
// keyframe M = T R S is split into a translation T, a rotation R (polar decomposition) and
// the remaining symmetric scale/shear S; at time t in [startTime, endTime] T and S are
// interpolated linearly and R along the shortest great arc (slerp); before startTime the
// start transform holds, after endTime the end one.
#pragma once
#include "math/transform.h"

namespace ps {

struct Quaternion {
    Vec3 v;
    float w = 1;
};
float dot(const Quaternion& a, const Quaternion& b);
Quaternion slerp(float t, const Quaternion& a, const Quaternion& b);
// The rotation matrix of a unit quaternion (upper-left 3x3 of the result).
Matrix4 rotationMatrix(const Quaternion& q);
// The unit quaternion of a rotation matrix (its upper-left 3x3; determinant +1).
Quaternion quaternionOf(const Matrix4& rotation);

// Where `time` lies between keyframes at `start` and `end`: 0 up to start, 1 from end on.
inline float keyframeFraction(float time, float start, float end) {
    if (!(time > start)) return 0;
    if (time >= end) return 1;
    return (time - start) / (end - start);
}

class AnimatedTransform {
public:
    AnimatedTransform() = default;
    AnimatedTransform(const Transform& start, float startTime, const Transform& end, float endTime);

    // False when both keyframes are equal: then the start transform is the whole story.
    bool isAnimated() const { return animated_; }
    Transform interpolate(float time) const;
    // Where `time` lies between the keyframes, clamped to [0, 1] as interpolate clamps it.
    float fraction(float time) const { return keyframeFraction(time, startTime_, endTime_); }

    const Transform& start() const { return start_; }
    const Transform& end() const { return end_; }
    float startTime() const { return startTime_; }
    float endTime() const { return endTime_; }

    // The decomposition of keyframe k (0: start, 1: end): M = translate(T) R(q) S, S in the
    // upper-left 3x3 of a Matrix4. q[1] is on q[0]'s side (dot >= 0), the shortest arc.
    Vec3 translation(int k) const { return T_[k]; }
    const Quaternion& rotation(int k) const { return R_[k]; }
    const Matrix4& scale(int k) const { return S_[k]; }

private:
    Transform start_, end_;
    float startTime_ = 0, endTime_ = 1;
    bool animated_ = false;
    Vec3 T_[2];
    Quaternion R_[2];
    Matrix4 S_[2];
};

}  // namespace ps
