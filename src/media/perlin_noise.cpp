#include "media/perlin_noise.h"

#include <cmath>

namespace ps {

namespace {

// Perlin's reference permutation of 0..255, stored twice so that chained lookups of a
// lattice coordinate plus a table value (at most 255 + 256) need no wrap.
constexpr int kPermutation[256] = {
    151, 160, 137, 91, 90, 15, 131, 13, 201, 95, 96, 53, 194, 233, 7, 225,
    140, 36, 103, 30, 69, 142, 8, 99, 37, 240, 21, 10, 23, 190, 6, 148,
    247, 120, 234, 75, 0, 26, 197, 62, 94, 252, 219, 203, 117, 35, 11, 32,
    57, 177, 33, 88, 237, 149, 56, 87, 174, 20, 125, 136, 171, 168, 68, 175,
    74, 165, 71, 134, 139, 48, 27, 166, 77, 146, 158, 231, 83, 111, 229, 122,
    60, 211, 133, 230, 220, 105, 92, 41, 55, 46, 245, 40, 244, 102, 143, 54,
    65, 25, 63, 161, 1, 216, 80, 73, 209, 76, 132, 187, 208, 89, 18, 169,
    200, 196, 135, 130, 116, 188, 159, 86, 164, 100, 109, 198, 173, 186, 3, 64,
    52, 217, 226, 250, 124, 123, 5, 202, 38, 147, 118, 126, 255, 82, 85, 212,
    207, 206, 59, 227, 47, 16, 58, 17, 182, 189, 28, 42, 223, 183, 170, 213,
    119, 248, 152, 2, 44, 154, 163, 70, 221, 153, 101, 155, 167, 43, 172, 9,
    129, 22, 39, 253, 19, 98, 108, 110, 79, 113, 224, 232, 178, 185, 112, 104,
    218, 246, 97, 228, 251, 34, 242, 193, 238, 210, 144, 12, 191, 179, 162, 241,
    81, 51, 145, 235, 249, 14, 239, 107, 49, 192, 214, 31, 181, 199, 106, 157,
    184, 84, 204, 176, 115, 121, 50, 45, 127, 4, 150, 254, 138, 236, 205, 93,
    222, 114, 67, 29, 24, 72, 243, 141, 128, 195, 78, 66, 215, 61, 156, 180,};

struct PermutationTable {
    int p[512];
    constexpr PermutationTable() : p() {
        for (int i = 0; i < 512; ++i) p[i] = kPermutation[i & 255];
    }
};
constexpr PermutationTable kTable;

// The gradient of each of the 16 hash values, as pbrt-v4 chooses them: twelve edge directions
// of the cube, four of them (12..15) repeated so that a 4-bit hash picks one.
constexpr signed char kGradient[16][3] = {
    {1, 1, 0}, {-1, 1, 0}, {1, -1, 0}, {-1, -1, 0}, {1, 0, 1}, {-1, 0, 1}, {1, 0, -1}, {-1, 0, -1},
    {0, 1, 1}, {0, -1, 1}, {0, 1, -1}, {0, -1, -1}, {1, 1, 0}, {-1, 1, 0}, {0, 1, -1}, {0, -1, -1},
};

float cornerTerm(int x, int y, int z, float dx, float dy, float dz) {
    const signed char* g = kGradient[kTable.p[kTable.p[kTable.p[x] + y] + z] & 15];
    return g[0] * dx + g[1] * dy + g[2] * dz;
}

// Perlin's quintic fade 6t^5 - 15t^4 + 10t^3: C2 across cell faces.
float fade(float t) {
    const float t2 = t * t, t3 = t2 * t;
    return 6 * (t2 * t2 * t) - 15 * (t2 * t2) + 10 * t3;
}

float mix(float t, float a, float b) { return (1 - t) * a + t * b; }

}  // namespace

float perlinNoise(Vec3 p) {
    const float kWrap = float(1 << 30);
    const float x = std::fmod(p.x, kWrap), y = std::fmod(p.y, kWrap), z = std::fmod(p.z, kWrap);
    int ix = int(std::floor(x)), iy = int(std::floor(y)), iz = int(std::floor(z));
    const float dx = x - float(ix), dy = y - float(iy), dz = z - float(iz);
    ix &= 255;
    iy &= 255;
    iz &= 255;
    const float wx = fade(dx), wy = fade(dy), wz = fade(dz);
    // Blend the eight corners' gradient terms along x, then y, then z.
    const float y0 = mix(wy, mix(wx, cornerTerm(ix, iy, iz, dx, dy, dz), cornerTerm(ix + 1, iy, iz, dx - 1, dy, dz)),
                         mix(wx, cornerTerm(ix, iy + 1, iz, dx, dy - 1, dz), cornerTerm(ix + 1, iy + 1, iz, dx - 1, dy - 1, dz)));
    const float y1 = mix(wy, mix(wx, cornerTerm(ix, iy, iz + 1, dx, dy, dz - 1), cornerTerm(ix + 1, iy, iz + 1, dx - 1, dy, dz - 1)),
                         mix(wx, cornerTerm(ix, iy + 1, iz + 1, dx, dy - 1, dz - 1),
                             cornerTerm(ix + 1, iy + 1, iz + 1, dx - 1, dy - 1, dz - 1)));
    return mix(wz, y0, y1);
}

Vec3 perlinNoiseDifference(Vec3 p) {
    const float h = 0.01f, n = perlinNoise(p);
    // Divided, not multiplied by 1/h, for pbrt-v4's rounding.
    return Vec3((perlinNoise(p + Vec3(h, 0, 0)) - n) / h, (perlinNoise(p + Vec3(0, h, 0)) - n) / h,
                (perlinNoise(p + Vec3(0, 0, h)) - n) / h);
}

}  // namespace ps
