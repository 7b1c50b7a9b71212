// Trowbridge-Reitz: normalisation of D and of the visible-normal density, Smith masking,
// the roughness conventions, and sampling of visible normals (Heitz 2018) by chi-square.
#include <gtest/gtest.h>

#include <cstdio>

#include "materials/fresnel.h"
#include "materials/microfacet.h"
#include "stats.h"

using namespace ps;
using namespace ps::test;

namespace {

constexpr int kChiSquareTests = 80;  // shared family size with bxdf_test.cpp
const double kAlpha = sidak(1e-3, kChiSquareTests);

struct Alphas {
    float ax, ay;
};
const Alphas kAlphas[] = {{0.05f, 0.05f}, {0.2f, 0.2f}, {0.6f, 0.6f}, {1.0f, 1.0f}, {0.1f, 0.5f}, {0.8f, 0.15f}};

// Projected microfacet area equals the macrosurface area: integral of D(wm) cos(theta_m) = 1.
TEST(TrowbridgeReitz, DistributionIsNormalised) {
    for (Alphas a : kAlphas) {
        TrowbridgeReitz d(a.ax, a.ay);
        double i = integrateSphere([&](Vec3 wm) { return wm.z > 0 ? d.D(wm) * wm.z : 0.0; }, 800, 400);
        EXPECT_NEAR(i, 1.0, 5e-3) << a.ax << "," << a.ay;
    }
}

// The visible-normal density D_wo(wm) = G1(wo) / |cos wo| D(wm) |wo.wm| (over wm with
// wo.wm > 0) integrates to 1: this is the definition of Smith's G1.
TEST(TrowbridgeReitz, VisibleNormalsAreNormalised) {
    for (Alphas a : kAlphas) {
        TrowbridgeReitz d(a.ax, a.ay);
        for (float cosO : {0.99f, 0.6f, 0.2f, 0.05f}) {
            Vec3 wo = directionAt(cosO, 0.7f);
            double i = integrateSphere([&](Vec3 wm) { return wm.z > 0 && dot(wo, wm) > 0 ? d.D(wo, wm) : 0.0; }, 800, 400);
            EXPECT_NEAR(i, 1.0, 6e-3) << a.ax << "," << a.ay << " cos=" << cosO;
        }
    }
}

TEST(TrowbridgeReitz, SmithMasking) {
    TrowbridgeReitz d(0.3f, 0.3f);
    Vec3 n(0, 0, 1);
    EXPECT_NEAR(d.G1(n), 1.0f, 1e-6f);
    EXPECT_NEAR(d.lambda(n), 0.0f, 1e-6f);
    // Isotropic closed form: Lambda = (sqrt(1 + a^2 tan^2) - 1) / 2.
    Vec3 w = directionAt(0.5f);
    float t2 = (1 - 0.25f) / 0.25f;
    EXPECT_NEAR(d.lambda(w), (std::sqrt(1 + 0.09f * t2) - 1) / 2, 1e-6f);
    Rng rng(3);
    for (int i = 0; i < 1000; ++i) {
        Vec3 wo = directionAt(rng.uniform(), 6.28f * rng.uniform()), wi = directionAt(rng.uniform(), 6.28f * rng.uniform());
        float g = d.G(wo, wi);
        EXPECT_LE(g, std::min(d.G1(wo), d.G1(wi)) + 1e-6f);  // height correlation: G >= G1 G1
        EXPECT_GE(g, d.G1(wo) * d.G1(wi) - 1e-6f);
        EXPECT_NEAR(d.G1(wo), d.G1(-wo), 1e-6f);
    }
}

TEST(TrowbridgeReitz, RoughnessConventions) {
    EXPECT_FLOAT_EQ(TrowbridgeReitz::roughnessToAlpha(0.25f), 0.5f);  // pbrt-v4: alpha = sqrt(roughness)
    EXPECT_TRUE(TrowbridgeReitz(9e-4f, 5e-4f).effectivelySmooth());
    EXPECT_FALSE(TrowbridgeReitz(1e-3f, 0).effectivelySmooth());
    TrowbridgeReitz clamped(2e-3f, 0);  // not smooth: both alphas at least 1e-4
    EXPECT_FLOAT_EQ(clamped.alphaY(), 1e-4f);
    EXPECT_FLOAT_EQ(clamped.alphaX(), 2e-3f);
}

// Sampled visible normals follow D_wo (chi-square on a (theta, phi) grid of the upper
// hemisphere); a wo below the surface samples the normals visible from -wo.
TEST(TrowbridgeReitz, VisibleNormalSamplingChiSquare) {
    const SphereGrid grid(20, 40);
    const int n = 200000;
    for (Alphas a : {kAlphas[1], kAlphas[2], kAlphas[4], kAlphas[5]}) {
        TrowbridgeReitz d(a.ax, a.ay);
        for (float cosO : {0.9f, 0.25f, -0.5f}) {
            Vec3 wo = directionAt(cosO, 0.4f);
            Vec3 wv = wo.z < 0 ? -wo : wo;
            std::vector<double> expected =
                grid.integrate([&](Vec3 wm) { return wm.z > 0 && dot(wv, wm) > 0 ? d.D(wo, wm) : 0.0; }, 10);
            for (double& e : expected) e *= n;
            std::vector<double> observed(expected.size(), 0.0);
            Rng rng(11);
            for (int i = 0; i < n; ++i) {
                Vec3 wm = d.sampleVisibleNormal(wo, {rng.uniform(), rng.uniform()});
                ASSERT_NEAR(length(wm), 1.0f, 1e-4f);
                ASSERT_GT(wm.z, 0);
                observed[grid.cellOf(wm)] += 1;
            }
            ChiSquareResult r = chiSquare(observed, expected);
            EXPECT_GT(r.pValue, kAlpha) << a.ax << "," << a.ay << " cos=" << cosO << " chi2=" << r.chi2 << " dof=" << r.dof;
        }
    }
}

TEST(Fresnel, Dielectric) {
    EXPECT_NEAR(fresnelDielectric(1, 1.5f), 0.04f, 1e-6f);  // ((eta - 1) / (eta + 1))^2
    EXPECT_NEAR(fresnelDielectric(-1, 1.5f), 0.04f, 1e-6f);
    EXPECT_NEAR(fresnelDielectric(1, 1), 0.0f, 1e-7f);
    EXPECT_NEAR(fresnelDielectric(1e-4f, 1.5f), 1.0f, 1e-3f);     // grazing
    EXPECT_EQ(fresnelDielectric(-0.3f, 1.5f), 1.0f);              // inside, beyond the critical angle
    EXPECT_LT(fresnelDielectric(-0.8f, 1.5f), 1.0f);
    // Brewster's angle (tan theta = eta): the parallel polarisation vanishes, R = Rs / 2.
    float thetaB = std::atan(1.5f), c = std::cos(thetaB), ct = std::cos(std::asin(std::sin(thetaB) / 1.5f));
    float rs = (c - 1.5f * ct) / (c + 1.5f * ct);
    EXPECT_NEAR(fresnelDielectric(c, 1.5f), rs * rs / 2, 1e-6f);
    // Stokes: reflectance is the same from either side of a refraction pair.
    for (float cosI : {0.95f, 0.6f, 0.2f}) {
        float sinT = std::sqrt(1 - cosI * cosI) / 1.5f, cosT = std::sqrt(1 - sinT * sinT);
        EXPECT_NEAR(fresnelDielectric(cosI, 1.5f), fresnelDielectric(-cosT, 1.5f), 1e-5f);
        EXPECT_NEAR(fresnelDielectric(cosI, 1.5f), fresnelDielectric(cosT, 1 / 1.5f), 1e-5f);
    }
}

TEST(Fresnel, Conductor) {
    for (float cosI : {1.0f, 0.7f, 0.3f, 0.05f}) {
        // k = 0 reduces to the dielectric formula.
        EXPECT_NEAR(fresnelComplex(cosI, std::complex<float>(1.5f, 0)), fresnelDielectric(cosI, 1.5f), 1e-5f);
        // A purely imaginary index reflects everything.
        EXPECT_NEAR(fresnelComplex(cosI, std::complex<float>(0, 2.0f)), 1.0f, 1e-5f);
    }
    float n = 0.2f, k = 3.9f;
    EXPECT_NEAR(fresnelComplex(1, std::complex<float>(n, k)), ((n - 1) * (n - 1) + k * k) / ((n + 1) * (n + 1) + k * k), 1e-5f);
}

// The written-out complex arithmetic against std::complex's, in double precision, over the
// indices of real metals and beyond (n from 0.05 to 4, k from 0 to 10, every angle; small k
// with n < 1 takes the square root's other branch).
TEST(Fresnel, ConductorMatchesComplexArithmetic) {
    using C = std::complex<double>;
    double worst = 0;
    for (double n = 0.05; n < 4; n += 0.37)
        for (double k : {0.0, 0.02, 0.1, 0.3, 0.6, 1.0, 2.0, 4.0, 7.0, 10.0})
            for (double cosI = 0; cosI <= 1; cosI += 0.0625) {
                const C eta(n, k);
                const C cosT = std::sqrt(1.0 - (1 - cosI * cosI) / (eta * eta));
                const double expected =
                    (std::norm((eta * cosI - cosT) / (eta * cosI + cosT)) + std::norm((cosI - eta * cosT) / (cosI + eta * cosT))) / 2;
                worst = std::max(worst, std::abs(fresnelComplex(float(cosI), std::complex<float>(float(n), float(k))) - expected));
            }
    std::printf("largest difference from double-precision complex arithmetic: %.2g\n", worst);
    EXPECT_LT(worst, 2e-6);
}

TEST(Fresnel, ReflectAndRefract) {
    Vec3 n(0, 0, 1), wo = normalize(Vec3(0.3f, 0.4f, 0.8f));
    Vec3 r = reflect(wo, n);
    EXPECT_NEAR(length(r - Vec3(-wo.x, -wo.y, wo.z)), 0, 1e-6f);
    Vec3 wt;
    float etap = 0;
    ASSERT_TRUE(refract(wo, n, 1.5f, &etap, &wt));
    EXPECT_FLOAT_EQ(etap, 1.5f);
    EXPECT_NEAR(length(wt), 1, 1e-5f);
    EXPECT_NEAR(std::sqrt(1 - wo.z * wo.z), 1.5f * std::sqrt(1 - wt.z * wt.z), 1e-5f);
    Vec3 back;
    ASSERT_TRUE(refract(wt, n, 1.5f, &etap, &back));  // from inside: relative index 1/1.5
    EXPECT_FLOAT_EQ(etap, 1 / 1.5f);
    EXPECT_NEAR(length(back - wo), 0, 1e-5f);
    EXPECT_FALSE(refract(directionAt(-0.2f), n, 1.5f, &etap, &wt));  // total internal reflection
}

}  // namespace
