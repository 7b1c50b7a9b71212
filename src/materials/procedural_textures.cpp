#include "materials/procedural_textures.h"

#include <algorithm>
#include <cmath>

namespace ps {

bool insidePolkaDot(Vec2 st) {
    // Cells are centred on the integer points; beyond float's exact integers there are none.
    const float sCell = std::floor(st.x + 0.5f), tCell = std::floor(st.y + 0.5f);
    if (!(std::fabs(sCell) < 1e7f) || !(std::fabs(tCell) < 1e7f)) return false;
    if (!(perlinNoise(sCell + 0.5f, tCell + 0.5f) > 0)) return false;
    constexpr float radius = 0.35f, maxShift = 0.5f - radius;
    const float sCentre = sCell + maxShift * perlinNoise(sCell + 1.5f, tCell + 2.8f);
    const float tCentre = tCell + maxShift * perlinNoise(sCell + 4.5f, tCell + 9.8f);
    const float ds = st.x - sCentre, dt = st.y - tCentre;
    return ds * ds + dt * dt < radius * radius;
}

float WindyTexture::evaluate(const TextureEvalContext& ctx) const {
    Vec3 q = map_.map(ctx);
    float windStrength = fbm(q * 0.1f, 0.5f, 3);
    float waveHeight = fbm(q, 0.5f, 6);
    return std::fabs(windStrength) * waveHeight;
}

Spectrum MarbleTexture::evaluate(const TextureEvalContext& ctx) const {
    Vec3 q = map_.map(ctx) * scale_;
    float t = 0.5f + 0.5f * std::sin(q.y + variation_ * fbm(q, omega_, octaves_));
    static const Spectrum colours[9] = {{.58f, .58f, .6f}, {.58f, .58f, .6f}, {.58f, .58f, .6f},
                                        {.5f, .5f, .5f},   {.6f, .59f, .58f}, {.58f, .58f, .6f},
                                        {.58f, .58f, .6f}, {.2f, .2f, .33f},  {.58f, .58f, .6f}};
    // Six overlapping segments of four control points each; t picks one and the place in it.
    constexpr int segments = 9 - 3;
    const float cell = std::floor(t * segments);
    const int first = cell >= 1 ? std::min(int(cell), segments - 1) : 0;
    const float u = t * segments - first;
    // The cubic Bezier curve through colours[first .. first + 3], in Bernstein form.
    const float v = 1 - u;
    const Spectrum* c = colours + first;
    Spectrum rgb = c[0] * (v * v * v) + c[1] * (3 * v * v * u) + c[2] * (3 * v * u * u) + c[3] * (u * u * u);
    return rgb * 1.5f;
}

}  // namespace ps
