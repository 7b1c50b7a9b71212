// Alpha cut-outs: a shape's "float alpha" or "texture alpha" (pbrt-v4's semantics, see
// PBRT-CONVENTIONS "Alpha"). At a ray hit the alpha a is evaluated there; a >= 1 keeps the hit,
// a <= 0 ignores it, and in between the hit is kept iff a number u in [0, 1) hashed from the
// ray is below a. The hash makes the test a fixed function of the query: tracing the same ray
// again gives the same answer, and in expectation a surface of alpha a blocks a fraction a.
#pragma once
#include <memory>
#include <optional>
#include "geometry/interaction.h"
#include "materials/texture.h"

namespace ps {

// A number in [0, 1) from the bit patterns of n floats (a 64-bit avalanche mix per value), the
// test's pseudo-random u: distinct inputs give uncorrelated outputs.
float hashToUnit(const float* values, int n);

class AlphaMask {
public:
    explicit AlphaMask(std::shared_ptr<const FloatTexture> alpha, std::optional<float> constant = std::nullopt)
        : alpha_(std::move(alpha)), constant_(constant) {}

    // The alpha at a point: the texture at (p, geometric normal, uv), as every query uses it.
    float value(Vec3 p, Vec3 n, Vec2 uv) const;
    // The stochastic test itself.
    static bool keeps(float a, float u) { return a >= 1 || (a > 0 && u < a); }
    // Whether the hit si of the ray (o, d) is kept. u is hashed from the ray and the hit
    // distance, so that two cut-out surfaces along one ray decide independently.
    bool keepsRayHit(const SurfaceInteraction& si, Vec3 o, Vec3 d) const;
    // Whether the point is present, u hashed from the point alone (how emitters decide: a point
    // sampled on an emitter and the same point hit by a ray get the same answer).
    bool keepsPoint(Vec3 p, Vec3 n, Vec2 uv) const;
    // Constant alpha 0: the shape is never hit.
    bool alwaysMasked() const { return constant_ && !(*constant_ > 0); }

private:
    std::shared_ptr<const FloatTexture> alpha_;
    std::optional<float> constant_;
};

}  // namespace ps
