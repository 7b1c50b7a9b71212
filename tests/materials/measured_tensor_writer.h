// Test-only: writes a small tensor file (the RGL .bsdf format pbrt-v4's "measured" material
// reads) for an analytic material, an isotropic GGX (Trowbridge-Reitz) microfacet reflector
// with a constant reflectance R in place of the Fresnel term:
//   f(wo, wi) = R D(wm) G2(wo, wi) / (4 cos(wo) cos(wi)).
// The tables are what the format defines for it: ndf = D, sigma = projected area
// cos(1 + Lambda), vndf = the visible normals' density in the unit square, and the
// reflectance in vndf's sample space, f cos(wi) / pdf_vndf(wi) = R G2 / G1(wo).
#pragma once
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "materials/fresnel.h"
#include "materials/microfacet.h"
#include "math/spectrum.h"
#include "mc/piecewise_linear_2d.h"

namespace ps::test {

struct TensorField {
    std::string name;
    uint8_t type;  // 1 = uint8, 10 = float32
    std::vector<uint64_t> shape;
    std::string bytes;
};

inline TensorField floatField(const std::string& name, std::vector<uint64_t> shape, const std::vector<float>& v) {
    TensorField f{name, 10, std::move(shape), std::string(v.size() * 4, '\0')};
    std::memcpy(f.bytes.data(), v.data(), f.bytes.size());
    return f;
}

// The file's bytes: header, then each field's data in order.
inline std::string tensorFileBytes(const std::vector<TensorField>& fields) {
    std::string head = std::string("tensor_file", 12) + std::string("\x01\x00", 2);
    auto put = [&](auto v) { head.append(reinterpret_cast<const char*>(&v), sizeof v); };
    put(uint32_t(fields.size()));
    size_t headerSize = head.size();
    for (const auto& f : fields) headerSize += 2 + f.name.size() + 2 + 1 + 8 + 8 * f.shape.size();
    uint64_t offset = headerSize;
    for (const auto& f : fields) {
        put(uint16_t(f.name.size()));
        head += f.name;
        put(uint16_t(f.shape.size()));
        put(f.type);
        put(offset);
        for (uint64_t s : f.shape) put(s);
        offset += f.bytes.size();
    }
    for (const auto& f : fields) head += f.bytes;
    return head;
}

inline void writeBytes(const std::string& path, const std::string& bytes) {
    std::ofstream(path, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
}

struct GgxTableSpec {
    float alpha = 0.4f;
    int n = 32;                     // the unit-square grids are n x n
    int nTheta = 12;                // theta_i values, 0 .. thetaMax
    float thetaMax = 1.45f;
    Spectrum R{0.9f, 0.6f, 0.3f};   // reflectance (rgb field)
    std::vector<float> wavelengths; // non-empty: a `spectra` field with R.g at every wavelength,
    std::vector<float> spectrum;    // or, when given, spectrum[l] at wavelengths[l]
};

// The fields of the file for spec (drop some to test the reader's errors).
inline std::vector<TensorField> ggxTensorFields(const GgxTableSpec& s) {
    const TrowbridgeReitz ggx(s.alpha, s.alpha);
    const int n = s.n, nt = s.nTheta;
    auto dirOf = [](float ux, float uy, float phiOffset) {
        float theta = ux * ux * (kPi / 2), phi = (2 * uy - 1) * kPi + phiOffset;
        return Vec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
    };
    auto at = [n](int i) { return float(i) / float(n - 1); };
    std::vector<float> thetaI(nt), phiI{0.0f};
    for (int k = 0; k < nt; ++k) thetaI[k] = s.thetaMax * float(k) / float(nt - 1);

    std::vector<float> ndf(n * n), sigma(n * n);
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            Vec3 w = dirOf(at(x), at(y), 0);
            ndf[y * n + x] = ggx.D(w);
            float c = std::max(0.0f, w.z), s2 = std::max(0.0f, 1 - c * c);
            sigma[y * n + x] = 0.5f * (c + std::sqrt(c * c + s.alpha * s.alpha * s2));  // cos (1 + Lambda)
        }
    std::vector<float> vndf(nt * n * n), lum(nt * n * n), refl(nt * n * n);
    for (int k = 0; k < nt; ++k) {
        Vec3 wo(std::sin(thetaI[k]), 0, std::cos(thetaI[k]));
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                Vec3 wm = dirOf(at(x), at(y), 0);
                float theta = at(x) * at(x) * (kPi / 2);
                float visible = ggx.G1(wo) / wo.z * ggx.D(wm) * std::max(0.0f, dot(wo, wm));
                vndf[(k * n + y) * n + x] = visible * 2 * kPi * kPi * at(x) * std::sin(theta);  // per unit square
            }
    }
    PiecewiseLinear2D vndfWarp(vndf.data(), n, n, {phiI, thetaI}, PiecewiseLinear2D::Mode::Warp);
    for (int k = 0; k < nt; ++k) {
        Vec3 wo(std::sin(thetaI[k]), 0, std::cos(thetaI[k]));
        float param[2] = {0, thetaI[k]};
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                Vec2 um = vndfWarp.sample(Vec2(at(x), at(y)), param).p;
                Vec3 wi = reflect(wo, dirOf(um.x, um.y, 0));
                float r = wi.z > 0 ? ggx.G(wo, wi) / ggx.G1(wo) : 0.0f;
                refl[(k * n + y) * n + x] = r;
                lum[(k * n + y) * n + x] = r;
            }
    }
    const uint64_t un = uint64_t(n), unt = uint64_t(nt);
    std::vector<TensorField> f = {
        floatField("theta_i", {unt}, thetaI), floatField("phi_i", {1}, phiI),
        floatField("ndf", {un, un}, ndf),     floatField("sigma", {un, un}, sigma),
        floatField("vndf", {1, unt, un, un}, vndf), floatField("luminance", {1, unt, un, un}, lum),
        TensorField{"description", 1, {4}, "test"}, TensorField{"jacobian", 1, {1}, std::string(1, '\1')},
    };
    const size_t plane = size_t(n) * n;
    if (s.wavelengths.empty()) {
        std::vector<float> rgb(nt * 3 * plane);
        for (int k = 0; k < nt; ++k)
            for (int c = 0; c < 3; ++c)
                for (size_t i = 0; i < plane; ++i) rgb[(k * 3 + c) * plane + i] = s.R[c] * refl[k * plane + i];
        f.push_back(floatField("rgb", {1, unt, 3, un, un}, rgb));
    } else {
        const size_t nl = s.wavelengths.size();
        std::vector<float> spectra(nt * nl * plane);
        for (int k = 0; k < nt; ++k)
            for (size_t l = 0; l < nl; ++l)
                for (size_t i = 0; i < plane; ++i)
                    spectra[(k * nl + l) * plane + i] = (s.spectrum.empty() ? s.R.g : s.spectrum[l]) * refl[k * plane + i];
        f.push_back(floatField("wavelengths", {nl}, s.wavelengths));
        f.push_back(floatField("spectra", {1, unt, nl, un, un}, spectra));
    }
    return f;
}

// The analytic BRDF the tables were made from.
inline Spectrum ggxReference(const GgxTableSpec& s, Vec3 wo, Vec3 wi) {
    if (wo.z <= 0 || wi.z <= 0) return {};
    const TrowbridgeReitz ggx(s.alpha, s.alpha);
    Vec3 wm = normalize(wo + wi);
    return s.R * (ggx.D(wm) * ggx.G(wo, wi) / (4 * wo.z * wi.z));
}

}  // namespace ps::test
