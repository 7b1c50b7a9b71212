// Every BxDF: energy conservation (white furnace), sample/eval consistency, reciprocity or
// the adjoint relation, and chi-square tests of sampled directions against pdf().
#include <gtest/gtest.h>

#include <functional>
#include <memory>
#include <vector>

#include "materials/coated_diffuse_bxdf.h"
#include "materials/conductor_bxdf.h"
#include "materials/dielectric_bxdf.h"
#include "materials/diffuse_bxdf.h"
#include "math/warp.h"
#include "mc/rng.h"

using namespace ps;

namespace {

struct Case {
    std::string name;
    std::function<std::unique_ptr<BxDF>()> make;
    bool conservesEnergy;  // furnace = 1 exactly (in Importance mode, no 1/eta^2)
    bool deterministic;    // f and pdf are exact functions (not stochastic estimates)
    bool smooth;           // only specular lobes
};

std::vector<Case> cases() {
    auto tr = [](float a) { return TrowbridgeReitz(a, a); };
    return {
        {"Diffuse", [] { return std::make_unique<DiffuseBxDF>(Spectrum(1.0f)); }, true, true, false},
        {"DiffuseTransmission", [] { return std::make_unique<DiffuseTransmissionBxDF>(Spectrum(0.3f), Spectrum(0.7f)); }, true, true, false},
        {"ConductorSmooth", [=] { return std::make_unique<ConductorBxDF>(tr(0), Spectrum(0.2f, 0.9f, 1.1f), Spectrum(3.9f, 2.4f, 2.1f)); }, false, true, true},
        {"ConductorRough03", [=] { return std::make_unique<ConductorBxDF>(tr(0.3f), Spectrum(0.2f, 0.9f, 1.1f), Spectrum(3.9f, 2.4f, 2.1f)); }, false, true, false},
        {"ConductorRough07", [=] { return std::make_unique<ConductorBxDF>(TrowbridgeReitz(0.7f, 0.2f), Spectrum(1.5f), Spectrum(5.0f)); }, false, true, false},
        {"DielectricSmooth", [=] { return std::make_unique<DielectricBxDF>(1.5f, tr(0)); }, true, true, true},
        {"DielectricSmoothInv", [=] { return std::make_unique<DielectricBxDF>(1 / 1.5f, tr(0)); }, true, true, true},
        {"DielectricRough02", [=] { return std::make_unique<DielectricBxDF>(1.5f, tr(0.2f)); }, false, true, false},
        {"DielectricRough05Inv", [=] { return std::make_unique<DielectricBxDF>(1 / 1.33f, tr(0.5f)); }, false, true, false},
        {"ThinDielectric", [] { return std::make_unique<ThinDielectricBxDF>(1.5f); }, true, true, true},
        {"CoatedDiffuseSmooth", [=] { CoatedDiffuseBxDF::Params p; p.reflectance = Spectrum(1.0f); p.thickness = 1e-4f;
                                       return std::make_unique<CoatedDiffuseBxDF>(p, tr(0)); }, false, false, false},
        {"CoatedDiffuseRough", [=] { CoatedDiffuseBxDF::Params p; p.reflectance = Spectrum(0.8f);
                                      return std::make_unique<CoatedDiffuseBxDF>(p, tr(0.3f)); }, false, false, false},
    };
}

Vec3 directionAt(float cosTheta) { return Vec3(safeSqrt(1 - cosTheta * cosTheta), 0, cosTheta); }

class BxDFTest : public ::testing::TestWithParam<Case> {};
// Sample/eval consistency, the adjoint relation and chi-square tests need exact f and pdf and
// non-specular lobes.
class BxDFExact : public ::testing::TestWithParam<Case> {};

std::vector<Case> exactCases() {
    std::vector<Case> out;
    for (const Case& c : cases())
        if (c.deterministic && !c.smooth) out.push_back(c);
    return out;
}

// E[f |cos| / pdf] over sampled directions = directional albedo; <= 1 always, = 1 when no
// energy is absorbed. Importance mode leaves out the radiance scaling of refraction.
TEST_P(BxDFTest, WhiteFurnace) {
    const Case& c = GetParam();
    auto b = c.make();
    Rng rng(101);
    for (float cosO : {0.95f, 0.6f, 0.2f, -0.5f}) {
        Vec3 wo = directionAt(cosO);
        const int n = 200000;
        double sum = 0, sum2 = 0;
        for (int i = 0; i < n; ++i) {
            auto s = b->sample(wo, rng.uniform(), {rng.uniform(), rng.uniform()}, TransportMode::Importance);
            double v = 0;
            if (s && s->pdf > 0) v = s->f.g * absCosTheta(s->wi) / s->pdf;
            ASSERT_TRUE(std::isfinite(v));
            sum += v;
            sum2 += v * v;
        }
        double mean = sum / n, se = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n);
        EXPECT_LE(mean, 1 + 4 * se + 1e-4) << c.name << " cos(wo)=" << cosO;
        if (c.conservesEnergy) {
            EXPECT_NEAR(mean, 1.0, 4 * se + 1e-4) << c.name << " cos(wo)=" << cosO;
        }
        EXPECT_GT(mean, 0.05) << c.name;
    }
}

// A sampled direction's f and pdf agree with f() and pdf() evaluated there.
TEST_P(BxDFExact, SampleMatchesEvaluation) {
    const Case& c = GetParam();
    auto b = c.make();
    Rng rng(7);
    for (int i = 0; i < 20000; ++i) {
        Vec3 wo = sampleUniformSphere({rng.uniform(), rng.uniform()});
        auto s = b->sample(wo, rng.uniform(), {rng.uniform(), rng.uniform()}, TransportMode::Radiance);
        if (!s) continue;
        Spectrum f = b->f(wo, s->wi, TransportMode::Radiance);
        float pdf = b->pdf(wo, s->wi, TransportMode::Radiance);
        ASSERT_NEAR(pdf, s->pdf, 2e-3f * std::max(1.0f, s->pdf)) << c.name;
        ASSERT_NEAR(f.g, s->f.g, 2e-3f * std::max(1.0f, s->f.g)) << c.name;
    }
}

// The adjoint relation f*(wo, wi) = f(wi, wo) (thesis §3.7.6): importance transport uses the
// transposed BSDF. For reflection it is plain reciprocity.
TEST_P(BxDFExact, AdjointAndReciprocity) {
    const Case& c = GetParam();
    auto b = c.make();
    Rng rng(9);
    for (int i = 0; i < 20000; ++i) {
        Vec3 wo = sampleUniformSphere({rng.uniform(), rng.uniform()});
        Vec3 wi = sampleUniformSphere({rng.uniform(), rng.uniform()});
        Spectrum a = b->f(wo, wi, TransportMode::Importance), r = b->f(wi, wo, TransportMode::Radiance);
        ASSERT_NEAR(a.g, r.g, 1e-3f * std::max(1.0f, r.g)) << c.name;
    }
}

// Pearson chi-square of sampled directions against pdf() integrated over (cos theta, phi)
// bins; bins with small expected counts are pooled. The pdf integrates to at most 1.
TEST_P(BxDFExact, ChiSquare) {
    const Case& c = GetParam();
    auto b = c.make();
    const int nT = 20, nP = 40, sub = 12, n = 500000;
    for (float cosO : {0.8f, 0.3f, -0.6f}) {
        Vec3 wo = directionAt(cosO);
        std::vector<double> expected(nT * nP, 0.0), observed(nT * nP, 0.0);
        double total = 0;
        for (int t = 0; t < nT; ++t)
            for (int p = 0; p < nP; ++p) {
                double acc = 0;
                for (int i = 0; i < sub; ++i)
                    for (int j = 0; j < sub; ++j) {
                        float ct = -1 + 2 * (t + (i + 0.5f) / sub) / nT, phi = 2 * kPi * (p + (j + 0.5f) / sub) / nP;
                        float st = safeSqrt(1 - ct * ct);
                        acc += b->pdf(wo, {st * std::cos(phi), st * std::sin(phi), ct}, TransportMode::Radiance);
                    }
                double cellArea = (2.0 / nT) * (2 * M_PI / nP);  // d(cos theta) d(phi)
                expected[t * nP + p] = acc / (sub * sub) * cellArea;
                total += expected[t * nP + p];
            }
        EXPECT_LE(total, 1.0 + 2e-2) << c.name << ": pdf integrates to more than 1";
        Rng rng(uint64_t(1000 * cosO) + 5);
        for (int i = 0; i < n; ++i) {
            auto s = b->sample(wo, rng.uniform(), {rng.uniform(), rng.uniform()}, TransportMode::Radiance);
            if (!s) continue;
            float ct = clampf(s->wi.z, -1, 1);
            float phi = std::atan2(s->wi.y, s->wi.x);
            if (phi < 0) phi += 2 * kPi;
            int t = std::min(nT - 1, int((ct + 1) / 2 * nT)), p = std::min(nP - 1, int(phi / (2 * kPi) * nP));
            observed[t * nP + p] += 1;
        }
        double chi2 = 0, pooledE = 0, pooledO = 0;
        int dof = 0;
        for (size_t k = 0; k < expected.size(); ++k) {
            double e = expected[k] * n;
            if (e < 5) {
                pooledE += e;
                pooledO += observed[k];
                continue;
            }
            chi2 += sqr(float(observed[k] - e)) / e;
            ++dof;
        }
        if (pooledE >= 5) {
            chi2 += (pooledO - pooledE) * (pooledO - pooledE) / pooledE;
            ++dof;
        }
        // Wilson-Hilferty quantile at significance ~1e-5 (z = 4.26), Sidak-safe over these tests.
        double k = std::max(1, dof - 1), z = 4.26;
        double limit = k * std::pow(1 - 2 / (9 * k) + z * std::sqrt(2 / (9 * k)), 3);
        EXPECT_LT(chi2, limit) << c.name << " cos(wo)=" << cosO << " dof=" << dof;
    }
}

INSTANTIATE_TEST_SUITE_P(All, BxDFTest, ::testing::ValuesIn(cases()),
                         [](const ::testing::TestParamInfo<Case>& i) { return i.param.name; });
INSTANTIATE_TEST_SUITE_P(All, BxDFExact, ::testing::ValuesIn(exactCases()),
                         [](const ::testing::TestParamInfo<Case>& i) { return i.param.name; });

}  // namespace
