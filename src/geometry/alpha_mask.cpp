#include "geometry/alpha_mask.h"

#include <cstdint>
#include <cstring>

#include "mc/rng.h"

namespace ps {

float hashToUnit(const float* values, int n) {
    uint64_t h = 0x9e3779b97f4a7c15ull;
    for (int i = 0; i < n; ++i) {
        float v = values[i] == 0 ? 0.0f : values[i];  // -0 and +0 are the same ray
        uint32_t bits;
        std::memcpy(&bits, &v, sizeof bits);
        h = mix64(h ^ (uint64_t(bits) + 0x632be59bd9b4e019ull * uint64_t(i + 1)));
    }
    return float(h >> 40) * 0x1p-24f;  // 24 bits: exactly representable, < 1
}

float AlphaMask::value(Vec3 p, Vec3 n, Vec2 uv) const {
    if (constant_) return *constant_;
    TextureEvalContext ctx;
    ctx.p = p;
    ctx.n = n;
    ctx.uv = uv;
    return alpha_->evaluate(ctx);
}

bool AlphaMask::keepsRayHit(const SurfaceInteraction& si, Vec3 o, Vec3 d) const {
    float a = value(si.p, si.ng, si.uv);
    if (a >= 1 || !(a > 0)) return a >= 1;
    const float key[7] = {o.x, o.y, o.z, d.x, d.y, d.z, si.t};
    return keeps(a, hashToUnit(key, 7));
}

bool AlphaMask::keepsPoint(Vec3 p, Vec3 n, Vec2 uv) const {
    float a = value(p, n, uv);
    if (a >= 1 || !(a > 0)) return a >= 1;
    const float key[3] = {p.x, p.y, p.z};
    return keeps(a, hashToUnit(key, 3));
}

}  // namespace ps
