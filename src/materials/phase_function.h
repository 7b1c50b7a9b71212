// The Henyey-Greenstein phase function (Henyey & Greenstein 1941), used inside layered
// BxDFs. Convention as for BxDFs: wo and wi both point away from the scattering point, so
// forward scattering (g > 0) favours wi = -wo.
#pragma once
#include "math/frame.h"
#include "math/vec.h"

namespace ps {

// p(cos) with cos = dot(wo, wi); |g| is kept below 0.99, where the lobe is still resolvable.
inline float henyeyGreenstein(float cosOI, float g) {
    g = clampf(g, -0.99f, 0.99f);
    float denom = 1 + g * g + 2 * g * cosOI;
    return kInv4Pi * (1 - g * g) / (denom * safeSqrt(denom));
}

class HGPhaseFunction {
public:
    explicit HGPhaseFunction(float g) : g_(clampf(g, -0.99f, 0.99f)) {}
    float p(Vec3 wo, Vec3 wi) const { return henyeyGreenstein(dot(wo, wi), g_); }
    float pdf(Vec3 wo, Vec3 wi) const { return p(wo, wi); }

    // Exact inversion of the HG cumulative distribution in the cosine mu between wi and the
    // propagation direction -wo; p is its own pdf.
    Vec3 sample(Vec3 wo, Vec2 u, float* pdf) const {
        float mu;
        if (std::fabs(g_) < 1e-3f) {
            mu = 1 - 2 * u.x;
        } else {
            float s = (1 - g_ * g_) / (1 - g_ + 2 * g_ * u.x);
            mu = (1 + g_ * g_ - s * s) / (2 * g_);
        }
        mu = clampf(mu, -1, 1);
        float sinMu = safeSqrt(1 - mu * mu), phi = 2 * kPi * u.y;
        Frame f = Frame::fromNormal(-wo);
        Vec3 wi = f.toWorld(Vec3(sinMu * std::cos(phi), sinMu * std::sin(phi), mu));
        *pdf = p(wo, wi);
        return wi;
    }

private:
    float g_;
};

}  // namespace ps
