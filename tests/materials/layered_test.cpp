// Layered BxDFs (coateddiffuse, coatedconductor): determinism of the stochastic f and pdf,
// two-sidedness, flags, limits with closed forms, agreement of f() with sample(), and a
// chi-square test of sampled directions where the walk's weights are all one.
#include <gtest/gtest.h>

#include <memory>

#include "materials/layered_bxdf.h"
#include "materials/phase_function.h"
#include "math/warp.h"
#include "stats.h"

using namespace ps;
using namespace ps::test;

namespace {

constexpr int kChiSquareTests = 80;  // shared family size with bxdf_test.cpp
const double kAlpha = sidak(1e-3, kChiSquareTests);

LayerParams layer(float thickness, Spectrum albedo = Spectrum(0.0f), float g = 0, int maxDepth = 10, int nSamples = 1,
                  bool pbrtExitMis = true) {
    LayerParams p;
    p.pbrtExitMis = pbrtExitMis;
    p.thickness = thickness;
    p.albedo = albedo;
    p.g = g;
    p.maxDepth = maxDepth;
    p.nSamples = nSamples;
    return p;
}
TrowbridgeReitz tr(float a) { return TrowbridgeReitz(a, a); }
CoatedDiffuseBxDF coatedDiffuse(float eta, float alpha, Spectrum R, LayerParams p) {
    return CoatedDiffuseBxDF(DielectricBxDF(eta, tr(alpha)), DiffuseBxDF(R), p);
}
CoatedConductorBxDF coatedConductor(float eta, float alphaTop, float alphaBase, Spectrum ceta, Spectrum k, LayerParams p) {
    return CoatedConductorBxDF(DielectricBxDF(eta, tr(alphaTop)), ConductorBxDF(tr(alphaBase), ceta, k), p);
}
const Spectrum kCuEta(0.2f, 0.92f, 1.1f), kCuK(3.9f, 2.45f, 2.14f);

// Henyey-Greenstein: normalised, its samples have mean cosine g about the propagation
// direction -wo, and the returned pdf is p.
TEST(HGPhaseFunction, NormalisedWithMeanCosineG) {
    for (float g : {-0.7f, 0.0f, 0.5f, 0.9f}) {
        HGPhaseFunction ph(g);
        Vec3 wo = normalize(Vec3(0.2f, -0.5f, 0.7f));
        EXPECT_NEAR(integrateSphere([&](Vec3 wi) { return ph.p(wo, wi); }, 800, 400), 1.0, 2e-3) << g;
        Rng rng(2);
        MeanSE mu = meanAndError(100000, [&] {
            float pdf = 0;
            Vec3 wi = ph.sample(wo, {rng.uniform(), rng.uniform()}, &pdf);
            EXPECT_NEAR(pdf, ph.p(wo, wi), 1e-4f * std::max(1.0f, pdf));
            return double(dot(-wo, wi));
        });
        EXPECT_NEAR(mu.mean, g, 4 * mu.se + 1e-4) << g;
    }
}

TEST(Layered, DeterministicEstimates) {
    auto b = coatedDiffuse(1.5f, 0.3f, Spectrum(0.7f), layer(0.1f, Spectrum(0.5f), 0.3f));
    Rng rng(1);
    for (int i = 0; i < 200; ++i) {
        Vec3 wo = directionAt(rng.uniform(), 6.28f * rng.uniform()), wi = directionAt(rng.uniform(), 6.28f * rng.uniform());
        Spectrum a = b.f(wo, wi, TransportMode::Radiance), c = b.f(wo, wi, TransportMode::Radiance);
        EXPECT_EQ(a.r, c.r);
        EXPECT_EQ(a.b, c.b);
        EXPECT_EQ(b.pdf(wo, wi, TransportMode::Radiance), b.pdf(wo, wi, TransportMode::Radiance));
        auto s1 = b.sample(wo, 0.4f, {0.3f, 0.8f}, TransportMode::Radiance), s2 = b.sample(wo, 0.4f, {0.3f, 0.8f}, TransportMode::Radiance);
        ASSERT_EQ(bool(s1), bool(s2));
        if (s1) {
            EXPECT_EQ(s1->wi.x, s2->wi.x);
            EXPECT_EQ(s1->pdf, s2->pdf);
            EXPECT_TRUE(s1->pdfIsProportional);
        }
    }
}

// Both faces are coated: the BxDF seen from below is the mirror image of the one above.
TEST(Layered, TwoSided) {
    auto b = coatedDiffuse(1.5f, 0.2f, Spectrum(0.6f), layer(0.01f));
    Rng rng(2);
    for (int i = 0; i < 200; ++i) {
        Vec3 wo = directionAt(rng.uniform(), 6.28f * rng.uniform()), wi = directionAt(rng.uniform(), 6.28f * rng.uniform());
        EXPECT_EQ(b.f(wo, wi, TransportMode::Radiance).g, b.f(-wo, -wi, TransportMode::Radiance).g);
        EXPECT_EQ(b.pdf(wo, wi, TransportMode::Radiance), b.pdf(-wo, -wi, TransportMode::Radiance));
        auto s = b.sample(-wo, rng.uniform(), {rng.uniform(), rng.uniform()}, TransportMode::Radiance);
        if (s) {
            EXPECT_LT(s->wi.z, 0);
            EXPECT_TRUE(s->isReflection());
        }
        // The base is opaque: nothing reaches the other side (pdf keeps pbrt's uniform floor).
        EXPECT_TRUE(b.f(wo, -wi, TransportMode::Radiance).isBlack());
        EXPECT_NEAR(b.pdf(wo, -wi, TransportMode::Radiance), 0.1f / (4 * kPi), 1e-7f);
    }
}

TEST(Layered, Flags) {
    EXPECT_EQ(coatedDiffuse(1.5f, 0, Spectrum(0.5f), layer(0.01f)).flags(), kReflection | kSpecular | kDiffuse);
    EXPECT_EQ(coatedDiffuse(1.5f, 0.3f, Spectrum(0.5f), layer(0.01f)).flags(), kReflection | kDiffuse);
    EXPECT_EQ(coatedDiffuse(1.5f, 0, Spectrum(0.0f), layer(0.01f)).flags(), kReflection | kSpecular);  // black base
    EXPECT_EQ(coatedConductor(1.5f, 0, 0, kCuEta, kCuK, layer(0.01f)).flags(), kReflection | kSpecular);
    EXPECT_EQ(coatedConductor(1.5f, 0, 0.3f, kCuEta, kCuK, layer(0.01f)).flags(), kReflection | kSpecular | kGlossy);
    EXPECT_EQ(coatedConductor(1.5f, 0.2f, 0.3f, kCuEta, kCuK, layer(0.01f)).flags(), kReflection | kGlossy);
    EXPECT_EQ(coatedConductor(1.5f, 0, 0, kCuEta, kCuK, layer(0.01f, Spectrum(0.5f))).flags(), kReflection | kSpecular | kDiffuse);
}

// With an index-1 coating of negligible thickness the layer is its base: the first
// next-event estimate is exact and every later bounce is lost through the invisible coating.
TEST(Layered, InvisibleCoatingIsTheBase) {
    auto cd = coatedDiffuse(1.0f, 0, Spectrum(0.2f, 0.5f, 0.9f), layer(0));
    ConductorBxDF base(tr(0.3f), kCuEta, kCuK);
    auto cc = coatedConductor(1.0f, 0, 0.3f, kCuEta, kCuK, layer(0));
    Rng rng(4);
    for (int i = 0; i < 100; ++i) {
        Vec3 wo = directionAt(0.05f + 0.95f * rng.uniform(), 6.28f * rng.uniform());
        Vec3 wi = directionAt(0.05f + 0.95f * rng.uniform(), 6.28f * rng.uniform());
        Spectrum f = cd.f(wo, wi, TransportMode::Radiance);
        EXPECT_NEAR(f.r, 0.2f / kPi, 1e-5f);
        EXPECT_NEAR(f.b, 0.9f / kPi, 1e-5f);
        Spectrum fc = cc.f(wo, wi, TransportMode::Radiance), fb = base.f(wo, wi, TransportMode::Radiance);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(fc[c], fb[c], 1e-4f * std::max(1.0f, fb[c]));
    }
}

// The directional albedo from sample() (E[f cos / pdf]) and from f() (cosine-weighted
// quadrature of f, plus the coating's specular reflection, which f() excludes) estimate the
// same quantity when the exit MIS weights are consistent (pbrtExitMis = false). maxDepth
// is large where the medium scatters: pbrt's f() counts one more event than sample() at the
// depth limit.
struct Config {
    const char* name;
    std::function<std::unique_ptr<BxDF>()> make;
    float topEta;
    bool topSmooth;
};

std::vector<Config> configs(bool pbrtExitMis) {
    const bool m = pbrtExitMis;
    return {
        {"CoatedDiffuseSmooth", [=] { return std::make_unique<CoatedDiffuseBxDF>(coatedDiffuse(1.5f, 0, Spectrum(0.8f), layer(0.01f, Spectrum(0.0f), 0, 10, 1, m))); }, 1.5f, true},
        {"CoatedDiffuseRough", [=] { return std::make_unique<CoatedDiffuseBxDF>(coatedDiffuse(1.5f, 0.3f, Spectrum(0.8f), layer(0.01f, Spectrum(0.0f), 0, 10, 1, m))); }, 1.5f, false},
        {"CoatedDiffuseMedium", [=] { return std::make_unique<CoatedDiffuseBxDF>(coatedDiffuse(1.3f, 0, Spectrum(0.6f), layer(0.3f, Spectrum(0.8f), -0.3f, 60, 1, m))); }, 1.3f, true},
        {"CoatedDiffuseRoughMedium", [=] { return std::make_unique<CoatedDiffuseBxDF>(coatedDiffuse(1.5f, 0.2f, Spectrum(0.9f), layer(0.2f, Spectrum(0.9f), 0.6f, 60, 1, m))); }, 1.5f, false},
        {"CoatedConductorRoughRough", [=] { return std::make_unique<CoatedConductorBxDF>(coatedConductor(1.5f, 0.3f, 0.2f, kCuEta / 1.5f, kCuK / 1.5f, layer(0.01f, Spectrum(0.0f), 0, 10, 1, m))); }, 1.5f, false},
        {"CoatedConductorSmoothRough", [=] { return std::make_unique<CoatedConductorBxDF>(coatedConductor(1.5f, 0, 0.4f, kCuEta / 1.5f, kCuK / 1.5f, layer(0.01f, Spectrum(0.0f), 0, 10, 1, m))); }, 1.5f, true},
        {"CoatedConductorRoughSmooth", [=] { return std::make_unique<CoatedConductorBxDF>(coatedConductor(1.5f, 0.3f, 0, kCuEta / 1.5f, kCuK / 1.5f, layer(0.01f, Spectrum(0.0f), 0, 10, 1, m))); }, 1.5f, false},
    };
}

TEST(Layered, AlbedoFromFMatchesSampling) {
    for (const Config& c : configs(false)) {
        auto b = c.make();
        for (float cosO : {0.9f, 0.4f}) {
            Vec3 wo = directionAt(cosO);
            for (TransportMode mode : {TransportMode::Radiance, TransportMode::Importance}) {
                MeanSE s = furnace(*b, wo, mode, 40000, 31);
                Rng rng(77);
                MeanSE f = meanAndError(40000, [&] {
                    Vec3 wi = sampleCosineHemisphere({rng.uniform(), rng.uniform()});
                    return double(b->f(wo, wi, mode).g) * kPi;  // f cos / (cos / pi)
                });
                double spec = c.topSmooth ? fresnelDielectric(cosO, c.topEta) : 0.0;
                double tol = 4 * std::sqrt(s.se * s.se + f.se * f.se) + 2e-3;
                std::printf("[ layered  ] %-28s cos(wo)=%.1f %s albedo: sample %.4f±%.4f, f %.4f±%.4f\n", c.name, cosO,
                            mode == TransportMode::Radiance ? "radiance  " : "importance", s.mean, s.se, f.mean + spec, f.se);
                EXPECT_NEAR(s.mean, f.mean + spec, tol) << c.name << " cos(wo)=" << cosO;
                EXPECT_LE(s.mean, 1 + 4 * s.se);
            }
        }
    }
}

// With a white base, a smooth coating, no absorption and Tr = 1, every step of the walk
// has weight f cos / pdf = 1 in importance mode (no Russian roulette), so sample() draws
// directions with density exactly E[f(wo, wi)] |cos wi| (plus the specular reflection):
// chi-square against f() averaged over each cell.
TEST(Layered, SampledDirectionsFollowF) {
    struct Setup {
        const char* name;
        float eta;
        LayerParams layer;
    };
    const Setup setups[] = {
        {"NoMedium", 1.5f, layer(0)},
        {"WhiteMedium", 1.4f, layer(0.3f, Spectrum(1.0f), 0.5f, 80)},
    };
    const TransportMode mode = TransportMode::Importance;
    const SphereGrid grid(10, 20);
    const int n = 100000, perCell = 1500;
    for (const Setup& st : setups) {
        auto b = coatedDiffuse(st.eta, 0, Spectrum(1.0f), st.layer);
        for (float cosO : {0.85f, 0.3f}) {
            Vec3 wo = directionAt(cosO);
            // Expected counts: Monte Carlo integrals of f cos over each cell (uniform points
            // in (cos theta, phi), one walk each), with their variances.
            std::vector<double> expected(grid.cells() + 1, 0.0), variance(grid.cells() + 1, 0.0);
            Rng er(99);
            double total = 0, totalVar = 0;
            for (int t = 0; t < grid.nTheta / 2; ++t)
                for (int p = 0; p < grid.nPhi; ++p) {
                    float c0 = std::cos((t + 1) * kPi / grid.nTheta), c1 = std::cos(t * kPi / grid.nTheta);
                    double area = (c1 - c0) * 2 * kPi / grid.nPhi;
                    MeanSE m = meanAndError(perCell, [&] {
                        float c = c0 + (c1 - c0) * er.uniform(), phi = (p + er.uniform()) * 2 * kPi / grid.nPhi;
                        Vec3 wi = directionAt(c, phi);
                        return double(b.f(wo, wi, mode).g) * c;
                    });
                    int cell = t * grid.nPhi + p;
                    expected[cell] = m.mean * area * n;
                    variance[cell] = (m.se * area * n) * (m.se * area * n);
                    total += m.mean * area;
                    totalVar += variance[cell];
                }
            float R = fresnelDielectric(cosO, st.eta);
            expected[grid.cellOf(Vec3(-wo.x, -wo.y, wo.z))] += R * n;
            expected[grid.cells()] = std::max(0.0, 1 - total - R) * n;
            variance[grid.cells()] = totalVar;
            std::vector<double> observed(expected.size(), 0.0);
            Rng rng(123);
            // Sample weights are 1, except after Russian roulette on a tiny throughput x: the walk
            // survives with probability 1 - float(1 - x), exact but not x. Allow a few such paths.
            int offWeight = 0;
            for (int i = 0; i < n; ++i) {
                float uc = rng.uniform();
                Vec2 u(rng.uniform(), rng.uniform());
                auto s = b.sample(wo, uc, u, mode);
                if (s && std::fabs(s->f.g * std::fabs(s->wi.z) / s->pdf - 1.0f) > 1e-3f) ++offWeight;
                observed[s ? grid.cellOf(s->wi) : grid.cells()] += 1;
            }
            EXPECT_LE(offWeight, n / 10000) << st.name << " cos(wo)=" << cosO;
            ChiSquareResult r = chiSquare(observed, expected, variance);
            std::printf("[ chi2     ] Layered%-21s cos(wo)=%5.2f chi2=%8.1f dof=%3d p=%.3g (albedo from f %.4f)\n", st.name, cosO,
                        r.chi2, r.dof, r.pValue, total + R);
            EXPECT_GT(r.pValue, kAlpha) << st.name << " cos(wo)=" << cosO << " chi2=" << r.chi2 << " dof=" << r.dof;
        }
    }
}

// pbrt-v4's MIS weight for leaving a rough coating (reverse-direction density) makes f()
// larger than the consistent estimator; with a smooth coating there is no MIS and the two
// agree exactly. Kept as pbrt's behaviour, measured here so a change is noticed.
TEST(Layered, PbrtExitMisOverestimatesRoughCoatings) {
    Vec3 wo = directionAt(0.7f);
    for (float alpha : {0.0f, 0.3f}) {
        auto pbrt = coatedDiffuse(1.5f, alpha, Spectrum(1.0f), layer(0.01f, Spectrum(0.0f), 0, 10, 1, true));
        auto consistent = coatedDiffuse(1.5f, alpha, Spectrum(1.0f), layer(0.01f, Spectrum(0.0f), 0, 10, 1, false));
        Rng r1(5), r2(5);
        auto albedo = [&](const BxDF& b, Rng& rng) {
            return meanAndError(100000, [&] {
                Vec3 wi = sampleCosineHemisphere({rng.uniform(), rng.uniform()});
                return double(b.f(wo, wi, TransportMode::Radiance).g) * kPi;
            });
        };
        MeanSE a = albedo(pbrt, r1), c = albedo(consistent, r2);
        std::printf("[ layered  ] coating alpha %.1f: albedo from f with pbrt-v4's exit MIS %.4f, consistent %.4f\n", alpha, a.mean, c.mean);
        if (alpha == 0) {
            EXPECT_EQ(a.mean, c.mean);
        } else {
            EXPECT_GT(a.mean - c.mean, 0.01);
            EXPECT_LT(a.mean - c.mean, 0.08);
        }
    }
}

// pbrt-v4's pdf() is an approximation (reflection at the coating plus single
// transmit-reflect-transmit paths, mixed with a uniform density): positive and finite
// wherever f is not zero, not normalised.
TEST(Layered, PdfIsPositiveWhereFIs) {
    for (const Config& c : configs(true)) {
        auto b = c.make();
        Vec3 wo = directionAt(0.6f);
        double integral = integrateSphere([&](Vec3 wi) { return b->pdf(wo, wi, TransportMode::Radiance); }, 100, 100);
        std::printf("[ layered  ] %-28s integral of pdf() over the sphere: %.3f\n", c.name, integral);
        EXPECT_GT(integral, 0.1);
        EXPECT_LT(integral, 3.0);
        Rng rng(8);
        for (int i = 0; i < 200; ++i) {
            Vec3 wi = sampleCosineHemisphere({rng.uniform(), rng.uniform()});
            float p = b->pdf(wo, wi, TransportMode::Radiance);
            EXPECT_TRUE(std::isfinite(p));
            EXPECT_GE(p, 0.1f / (4 * kPi) * 0.999f);
        }
    }
}

}  // namespace
