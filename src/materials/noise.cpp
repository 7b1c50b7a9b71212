#include "materials/noise.h"

#include <cmath>

namespace ps {

namespace {

// Ken Perlin's permutation of 0..255: part of the noise function's definition (the lattice
// gradients are picked through it), so the same table gives the same noise as pbrt-v4.
constexpr unsigned char kPerm[256] = {
    151, 160, 137,  91,  90,  15, 131,  13, 201,  95,  96,  53, 194, 233,   7, 225,
    140,  36, 103,  30,  69, 142,   8,  99,  37, 240,  21,  10,  23, 190,   6, 148,
    247, 120, 234,  75,   0,  26, 197,  62,  94, 252, 219, 203, 117,  35,  11,  32,
     57, 177,  33,  88, 237, 149,  56,  87, 174,  20, 125, 136, 171, 168,  68, 175,
     74, 165,  71, 134, 139,  48,  27, 166,  77, 146, 158, 231,  83, 111, 229, 122,
     60, 211, 133, 230, 220, 105,  92,  41,  55,  46, 245,  40, 244, 102, 143,  54,
     65,  25,  63, 161,   1, 216,  80,  73, 209,  76, 132, 187, 208,  89,  18, 169,
    200, 196, 135, 130, 116, 188, 159,  86, 164, 100, 109, 198, 173, 186,   3,  64,
     52, 217, 226, 250, 124, 123,   5, 202,  38, 147, 118, 126, 255,  82,  85, 212,
    207, 206,  59, 227,  47,  16,  58,  17, 182, 189,  28,  42, 223, 183, 170, 213,
    119, 248, 152,   2,  44, 154, 163,  70, 221, 153, 101, 155, 167,  43, 172,   9,
    129,  22,  39, 253,  19,  98, 108, 110,  79, 113, 224, 232, 178, 185, 112, 104,
    218, 246,  97, 228, 251,  34, 242, 193, 238, 210, 144,  12, 191, 179, 162, 241,
     81,  51, 145, 235, 249,  14, 239, 107,  49, 192, 214,  31, 181, 199, 106, 157,
    184,  84, 204, 176, 115, 121,  50,  45, 127,   4, 150, 254, 138, 236, 205,  93,
    222, 114,  67,  29,  24,  72, 243, 141, 128, 195,  78,  66, 215,  61, 156, 180,
};

int perm(int i) { return kPerm[i & 255]; }

// The dot product of lattice corner (x, y, z)'s gradient with the offset (dx, dy, dz) from
// it. The corner's hash h (0..15) picks one of 12 edge directions of a cube, (+-1, +-1, 0)
// and permutations; h = 12..15 repeat four of them.
float gradientDot(int x, int y, int z, float dx, float dy, float dz) {
    const int h = perm(perm(perm(x) + y) + z) & 15;
    const float a = (h < 8 || h == 12 || h == 13) ? dx : dy;
    const float b = (h < 4 || h == 12 || h == 13) ? dy : dz;
    return ((h & 1) ? -a : a) + ((h & 2) ? -b : b);
}

// 6t^5 - 15t^4 + 10t^3: zero first and second derivatives at the lattice.
float fade(float t) { return t * t * t * (t * (t * 6 - 15) + 10); }

}  // namespace

float perlinNoise(float x, float y, float z) {
    if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z)) return 0;
    // Keep the lattice coordinates within int range (the noise repeats every 256 anyway).
    constexpr float kWrap = float(1 << 30);
    x = std::fmod(x, kWrap);
    y = std::fmod(y, kWrap);
    z = std::fmod(z, kWrap);
    const float fx = std::floor(x), fy = std::floor(y), fz = std::floor(z);
    const float dx = x - fx, dy = y - fy, dz = z - fz;
    const int ix = int(fx) & 255, iy = int(fy) & 255, iz = int(fz) & 255;
    // The eight corners' contributions, blended trilinearly with faded weights.
    const float wx = fade(dx), wy = fade(dy), wz = fade(dz);
    float corner[2][2][2];
    for (int k = 0; k < 2; ++k)
        for (int j = 0; j < 2; ++j)
            for (int i = 0; i < 2; ++i) corner[k][j][i] = gradientDot(ix + i, iy + j, iz + k, dx - i, dy - j, dz - k);
    const float y0 = lerp(wy, lerp(wx, corner[0][0][0], corner[0][0][1]), lerp(wx, corner[0][1][0], corner[0][1][1]));
    const float y1 = lerp(wy, lerp(wx, corner[1][0][0], corner[1][0][1]), lerp(wx, corner[1][1][0], corner[1][1][1]));
    return lerp(wz, y0, y1);
}

Vec3 perlinNoiseDifference(Vec3 p) {
    const float h = 0.01f, n = perlinNoise(p);
    // Divided, not multiplied by 1/h, for pbrt-v4's rounding.
    return Vec3((perlinNoise(p + Vec3(h, 0, 0)) - n) / h, (perlinNoise(p + Vec3(0, h, 0)) - n) / h,
                (perlinNoise(p + Vec3(0, 0, h)) - n) / h);
}

float fbm(Vec3 p, float omega, int octaves) {
    float sum = 0, frequency = 1, amplitude = 1;
    for (int i = 0; i < octaves; ++i) {
        sum += amplitude * perlinNoise(p * frequency);
        frequency *= kOctaveLacunarity;
        amplitude *= omega;
    }
    return sum;
}

float turbulence(Vec3 p, float omega, int octaves) {
    float sum = 0, frequency = 1, amplitude = 1;
    for (int i = 0; i < octaves; ++i) {
        sum += amplitude * std::fabs(perlinNoise(p * frequency));
        frequency *= kOctaveLacunarity;
        amplitude *= omega;
    }
    // pbrt-v4 lets the octave beyond the last count at 0.2 (near |noise|'s mean, 0.22), the
    // value its filtered evaluation also gives octaves too fine to resolve.
    return sum + amplitude * 0.2f;
}

}  // namespace ps
