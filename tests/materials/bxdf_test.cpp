// Every BxDF: energy conservation (white furnace), sample/eval consistency, reciprocity and
// the adjoint relation, chi-square tests of sampled directions against pdf(), and the pdf's
// integral over the sphere. Fixed seeds throughout.
#include <gtest/gtest.h>

#include <cstdio>
#include <functional>
#include <memory>
#include <vector>

#include "materials/conductor_bxdf.h"
#include "materials/dielectric_bxdf.h"
#include "materials/diffuse_bxdf.h"
#include "materials/diffuse_transmission_bxdf.h"
#include "materials/layered_bxdf.h"
#include "materials/thin_dielectric_bxdf.h"
#include "math/warp.h"
#include "mc/rng.h"
#include "stats.h"

using namespace ps;
using namespace ps::test;

namespace {

// Significance of the whole family of chi-square tests in this executable (bxdf and
// microfacet); each test uses the Sidak-corrected level for this many tests (an upper bound).
constexpr int kChiSquareTests = 80;
const double kAlpha = sidak(1e-3, kChiSquareTests);

enum class Energy { Exact, AtMost };

struct Case {
    std::string name;
    std::function<std::unique_ptr<BxDF>()> make;
    Energy energy;        // Importance-mode furnace: = 1 exactly, or <= 1
    bool smooth;          // only delta lobes: f() and pdf() are zero
    bool stochastic;      // layered: f() and pdf() are estimates
    float etaBelow = 0;   // refractive index below the surface (above: 1); 0 if no refraction
    bool chiSquare = false;
};

TrowbridgeReitz tr(float ax, float ay) { return TrowbridgeReitz(ax, ay); }
TrowbridgeReitz tr(float a) { return TrowbridgeReitz(a, a); }

// A perfect mirror: purely imaginary index (eta = 0, k > 0) gives F = 1 at every angle.
const Spectrum kMirrorEta(0.0f), kMirrorK(1.0f);
const Spectrum kCuEta(0.2f, 0.92f, 1.1f), kCuK(3.9f, 2.45f, 2.14f);

template <typename T, typename... A>
std::function<std::unique_ptr<BxDF>()> mk(A... a) {
    return [=] { return std::unique_ptr<BxDF>(new T(a...)); };
}

std::function<std::unique_ptr<BxDF>()> coatedDiffuse(float eta, float alpha, Spectrum R, LayerParams p) {
    return [=] { return std::unique_ptr<BxDF>(new CoatedDiffuseBxDF(DielectricBxDF(eta, tr(alpha)), DiffuseBxDF(R), p)); };
}
std::function<std::unique_ptr<BxDF>()> coatedConductor(float eta, float alphaTop, float alphaBase, LayerParams p) {
    return [=] {
        return std::unique_ptr<BxDF>(new CoatedConductorBxDF(DielectricBxDF(eta, tr(alphaTop)), ConductorBxDF(tr(alphaBase), kMirrorEta, kMirrorK), p));
    };
}
LayerParams layer(float thickness, Spectrum albedo = Spectrum(0.0f), float g = 0, int maxDepth = 10, int nSamples = 1) {
    LayerParams p;
    p.thickness = thickness;
    p.albedo = albedo;
    p.g = g;
    p.maxDepth = maxDepth;
    p.nSamples = nSamples;
    return p;
}

std::vector<Case> cases() {
    using E = Energy;
    return {
        {"Diffuse", mk<DiffuseBxDF>(Spectrum(1.0f)), E::Exact, false, false, 0, true},
        {"DiffuseTransmission", mk<DiffuseTransmissionBxDF>(Spectrum(0.3f), Spectrum(0.7f)), E::Exact, false, false, 0, true},
        {"DiffuseTransmissionColoured", mk<DiffuseTransmissionBxDF>(Spectrum(0.9f, 0.2f, 0.1f), Spectrum(0.1f, 0.5f, 0.3f)), E::AtMost, false, false, 0, true},
        {"ConductorSmoothMirror", mk<ConductorBxDF>(tr(0), kMirrorEta, kMirrorK), E::Exact, true, false},
        {"ConductorSmoothCopper", mk<ConductorBxDF>(tr(0), kCuEta, kCuK), E::AtMost, true, false},
        {"ConductorRough01", mk<ConductorBxDF>(tr(0.1f), kMirrorEta, kMirrorK), E::AtMost, false, false, 0, true},
        {"ConductorRough03", mk<ConductorBxDF>(tr(0.3f), kMirrorEta, kMirrorK), E::AtMost, false, false, 0, true},
        {"ConductorRough07", mk<ConductorBxDF>(tr(0.7f), kMirrorEta, kMirrorK), E::AtMost, false, false, 0, true},
        {"ConductorRoughAniso", mk<ConductorBxDF>(tr(0.15f, 0.6f), kMirrorEta, kMirrorK), E::AtMost, false, false, 0, true},
        {"ConductorRoughCopper", mk<ConductorBxDF>(tr(0.3f), kCuEta, kCuK), E::AtMost, false, false, 0, true},
        {"DielectricSmooth15", mk<DielectricBxDF>(1.5f, tr(0)), E::Exact, true, false, 1.5f},
        {"DielectricSmoothInv15", mk<DielectricBxDF>(1 / 1.5f, tr(0)), E::Exact, true, false, 1 / 1.5f},
        {"DielectricPassThrough", mk<DielectricBxDF>(1.0f, tr(0.3f)), E::Exact, true, false, 1.0f},
        {"DielectricRough15a01", mk<DielectricBxDF>(1.5f, tr(0.1f)), E::AtMost, false, false, 1.5f, true},
        {"DielectricRough15a04", mk<DielectricBxDF>(1.5f, tr(0.4f)), E::AtMost, false, false, 1.5f, true},
        {"DielectricRoughInv15a03", mk<DielectricBxDF>(1 / 1.5f, tr(0.3f)), E::AtMost, false, false, 1 / 1.5f, true},
        {"DielectricRoughAniso133", mk<DielectricBxDF>(1.33f, tr(0.1f, 0.5f)), E::AtMost, false, false, 1.33f, true},
        {"ThinDielectric", mk<ThinDielectricBxDF>(1.5f), E::Exact, true, false},
        {"CoatedDiffuseSmooth", coatedDiffuse(1.5f, 0, Spectrum(1.0f), layer(1e-4f)), E::AtMost, false, true},
        {"CoatedDiffuseRough", coatedDiffuse(1.5f, 0.3f, Spectrum(0.8f), layer(0.01f)), E::AtMost, false, true},
        {"CoatedDiffuseMedium", coatedDiffuse(1.5f, 0.2f, Spectrum(1.0f), layer(0.5f, Spectrum(0.9f), 0.5f)), E::AtMost, false, true},
        {"CoatedConductorRough", coatedConductor(1.5f, 0.2f, 0.4f, layer(0.01f)), E::AtMost, false, true},
        {"CoatedConductorSmooth", coatedConductor(1.5f, 0, 0, layer(1e-4f)), E::AtMost, true, true},
    };
}

std::vector<Case> select(bool (*keep)(const Case&)) {
    std::vector<Case> out;
    for (const Case& c : cases())
        if (keep(c)) out.push_back(c);
    return out;
}

std::string caseName(const ::testing::TestParamInfo<Case>& i) { return i.param.name; }

class Furnace : public ::testing::TestWithParam<Case> {};
class Deterministic : public ::testing::TestWithParam<Case> {};  // exact, non-specular
class Smooth : public ::testing::TestWithParam<Case> {};         // exact, specular only
class Sampling : public ::testing::TestWithParam<Case> {};       // chi-square cases

// E[f |cos| / pdf] over sampled directions = directional albedo: <= 1 always, = 1 when no
// energy is absorbed. Importance mode leaves out the radiance scaling of refraction.
// bxdf_reference_test.cpp anchors the values of the rough and coated lobes against an
// independent reference.
TEST_P(Furnace, ImportanceSampledAlbedo) {
    const Case& c = GetParam();
    auto b = c.make();
    const int n = c.stochastic ? 40000 : 200000;
    std::string line;
    for (float cosO : {0.95f, 0.5f, 0.1f, -0.3f, -0.8f}) {
        // Through int64_t: a negative float converted straight to an unsigned type is undefined.
        MeanSE m = furnace(*b, directionAt(cosO), TransportMode::Importance, n, 101 + uint64_t(int64_t(cosO * 1000)));
        char buf[64];
        std::snprintf(buf, sizeof buf, " %.4f±%.4f", m.mean, m.se);
        line += buf;
        EXPECT_LE(m.mean, 1 + 4 * m.se + 1e-4) << c.name << " cos(wo)=" << cosO;
        if (c.energy == Energy::Exact) { EXPECT_NEAR(m.mean, 1.0, 4 * m.se + 1e-4) << c.name << " cos(wo)=" << cosO; }
        EXPECT_GT(m.mean, 0.05) << c.name << " cos(wo)=" << cosO;
    }
    std::printf("[ furnace  ] %-28s cos(wo)=0.95,0.5,0.1,-0.3,-0.8:%s\n", c.name.c_str(), line.c_str());
}

// In radiance mode a smooth dielectric's albedo is R + T / eta'^2 (the refracted radiance
// is compressed into a smaller solid angle, thesis §5.2).
// Integrators draw no lobe-choice number for BxDFs that say they ignore it.
TEST(LobeSample, IgnoredWhereFlagsSaySo) {
    std::vector<Case> all = cases();
    int checked = 0;
    for (const Case& c : all) {
        auto bxdf = c.make();
        if (bxdf->usesLobeSample()) continue;
        ++checked;
        Rng rng(11);
        for (int i = 0; i < 2000; ++i) {
            Vec3 wo = sampleUniformSphere({rng.uniform(), rng.uniform()});
            Vec2 u{rng.uniform(), rng.uniform()};
            float uc1 = rng.uniform(), uc2 = rng.uniform();
            for (TransportMode mode : {TransportMode::Radiance, TransportMode::Importance}) {
                auto a = bxdf->sample(wo, uc1, u, mode), b = bxdf->sample(wo, uc2, u, mode);
                ASSERT_EQ(bool(a), bool(b)) << c.name;
                if (!a) continue;
                EXPECT_EQ(a->wi.x, b->wi.x) << c.name;
                EXPECT_EQ(a->wi.y, b->wi.y) << c.name;
                EXPECT_EQ(a->wi.z, b->wi.z) << c.name;
                EXPECT_EQ(a->pdf, b->pdf) << c.name;
            }
        }
    }
    EXPECT_GE(checked, 7);  // diffuse and the conductors
}

TEST(SmoothDielectric, RadianceModeScalesRefraction) {
    for (float eta : {1.5f, 1 / 1.5f})
        for (float cosO : {0.9f, 0.4f, -0.4f, -0.95f}) {
            DielectricBxDF b(eta, tr(0));
            float R = fresnelDielectric(cosO, eta);
            float etap = cosO > 0 ? eta : 1 / eta;
            MeanSE m = furnace(b, directionAt(cosO), TransportMode::Radiance, 20000, 3);
            EXPECT_NEAR(m.mean, R + (1 - R) / (etap * etap), 4 * m.se + 1e-4) << "eta=" << eta << " cos=" << cosO;
        }
}

// A sampled direction's f and pdf agree with f() and pdf() evaluated there, in both modes.
TEST_P(Deterministic, SampleMatchesEvaluation) {
    const Case& c = GetParam();
    auto b = c.make();
    Rng rng(7);
    int checked = 0;
    for (TransportMode mode : {TransportMode::Radiance, TransportMode::Importance})
        for (int i = 0; i < 20000; ++i) {
            Vec3 wo = sampleUniformSphere({rng.uniform(), rng.uniform()});
            float uc = rng.uniform();
            Vec2 u(rng.uniform(), rng.uniform());
            auto s = b->sample(wo, uc, u, mode);
            if (!s) continue;
            ++checked;
            ASSERT_FALSE(s->isSpecular()) << c.name;
            ASSERT_FALSE(s->pdfIsProportional) << c.name;
            Spectrum f = b->f(wo, s->wi, mode);
            float pdf = b->pdf(wo, s->wi, mode);
            ASSERT_NEAR(pdf, s->pdf, 2e-3f * std::max(1.0f, s->pdf)) << c.name;
            for (int ch = 0; ch < 3; ++ch) ASSERT_NEAR(f[ch], s->f[ch], 2e-3f * std::max(1.0f, s->f[ch])) << c.name;
            // Transmission flags and the relative index follow the side of wi.
            ASSERT_EQ(s->isTransmission(), !sameHemisphere(wo, s->wi)) << c.name;
            if (c.etaBelow > 0 && s->isTransmission()) { ASSERT_NEAR(s->eta, wo.z > 0 ? c.etaBelow : 1 / c.etaBelow, 1e-5f); }
        }
    EXPECT_GT(checked, 20000) << c.name;
}

// Reciprocity f(wo, wi) = f(wi, wo) for reflection. Across a refracting interface
// f(wo, wi) / n(wo)^2 = f(wi, wo) / n(wi)^2 in radiance mode (thesis eq. 5.14), and
// importance mode is the adjoint f*(wo, wi) = f(wi, wo) (thesis §3.7.6).
TEST_P(Deterministic, ReciprocityAndAdjoint) {
    const Case& c = GetParam();
    auto b = c.make();
    Rng rng(9);
    auto n2 = [&](Vec3 w) { return c.etaBelow > 0 && w.z < 0 ? c.etaBelow * c.etaBelow : 1.0f; };
    int nonzero = 0;
    for (int i = 0; i < 20000; ++i) {
        Vec3 wo = sampleUniformSphere({rng.uniform(), rng.uniform()});
        Vec3 wi = sampleUniformSphere({rng.uniform(), rng.uniform()});
        Spectrum fr = b->f(wo, wi, TransportMode::Radiance), rr = b->f(wi, wo, TransportMode::Radiance);
        Spectrum fi = b->f(wo, wi, TransportMode::Importance);
        for (int ch = 0; ch < 3; ++ch) {
            float a = fr[ch] / n2(wo), r = rr[ch] / n2(wi);
            ASSERT_NEAR(a, r, 1e-3f * std::max({1.0f, a, r})) << c.name;
            ASSERT_NEAR(fi[ch], rr[ch], 1e-3f * std::max({1.0f, fi[ch], rr[ch]})) << c.name;
            ASSERT_GE(fr[ch], 0) << c.name;
        }
        if (!fr.isBlack()) ++nonzero;
    }
    EXPECT_GT(nonzero, 1000) << c.name;
}

// Pearson's chi-square of sampled directions against pdf() integrated over a 20 x 40
// (theta, phi) grid of the whole sphere, conditioned on the sample succeeding (the
// normalisation, i.e. the failure probability, is checked by the next test with a finer
// quadrature than the cells allow).
TEST_P(Sampling, ChiSquareAgainstPdf) {
    const Case& c = GetParam();
    auto b = c.make();
    const SphereGrid grid(20, 40);
    const int n = 300000;
    for (float cosO : {0.8f, 0.3f, -0.6f}) {
        Vec3 wo = directionAt(cosO);
        // Fine midpoint quadrature: rough transmission lobes are steep near the horizon.
        std::vector<double> expected = grid.integrate([&](Vec3 wi) { return b->pdf(wo, wi, TransportMode::Radiance); }, 32);
        std::vector<double> observed(expected.size(), 0.0);
        Rng rng(uint64_t(1000 + 1000 * cosO));
        double ok = 0;
        for (int i = 0; i < n; ++i) {
            float uc = rng.uniform();
            Vec2 u(rng.uniform(), rng.uniform());
            if (auto s = b->sample(wo, uc, u, TransportMode::Radiance)) {
                observed[grid.cellOf(s->wi)] += 1;
                ++ok;
            }
        }
        double total = 0;
        for (double e : expected) total += e;
        for (double& e : expected) e *= ok / total;
        ChiSquareResult r = chiSquare(observed, expected);
        std::printf("[ chi2     ] %-28s cos(wo)=%5.2f chi2=%8.1f dof=%3d p=%.3g\n", c.name.c_str(), cosO, r.chi2, r.dof, r.pValue);
        EXPECT_GT(r.pValue, kAlpha) << c.name << " cos(wo)=" << cosO << " chi2=" << r.chi2 << " dof=" << r.dof;
    }
}

// pdf() integrates to at most 1 over the sphere, and to the probability that sample()
// succeeds (samples below the horizon are rejected, their density is not returned).
TEST_P(Sampling, PdfIntegratesToSuccessProbability) {
    const Case& c = GetParam();
    auto b = c.make();
    for (float cosO : {0.9f, 0.4f, 0.05f, -0.7f}) {
        Vec3 wo = directionAt(cosO);
        // Lobes near the horizon are narrow in phi: a fine phi grid.
        double integral = integrateSphere([&](Vec3 wi) { return b->pdf(wo, wi, TransportMode::Radiance); }, 300, 1200);
        Rng rng(17);
        const int n = 100000;
        int ok = 0;
        for (int i = 0; i < n; ++i) {
            float uc = rng.uniform();
            Vec2 u(rng.uniform(), rng.uniform());
            if (b->sample(wo, uc, u, TransportMode::Radiance)) ++ok;
        }
        double p = double(ok) / n, se = std::sqrt(std::max(p * (1 - p), 1e-6) / n);
        EXPECT_LE(integral, 1 + 2e-3) << c.name << " cos(wo)=" << cosO;
        EXPECT_NEAR(integral, p, 4 * se + 2e-3) << c.name << " cos(wo)=" << cosO;
        std::printf("[ pdf      ] %-28s cos(wo)=%5.2f integral of pdf %.4f, P(sample succeeds) %.4f\n", c.name.c_str(), cosO, integral, p);
    }
}

// Purely specular BxDFs: f() and pdf() vanish, samples carry the Specular flag and the
// lobe probability as pdf.
TEST_P(Smooth, DeltaLobes) {
    const Case& c = GetParam();
    auto b = c.make();
    EXPECT_TRUE(b->isSpecular()) << c.name;
    Rng rng(5);
    for (int i = 0; i < 2000; ++i) {
        Vec3 wo = sampleUniformSphere({rng.uniform(), rng.uniform()});
        float uc = rng.uniform();
        Vec2 u(rng.uniform(), rng.uniform());
        auto s = b->sample(wo, uc, u, TransportMode::Radiance);
        if (!s) continue;
        EXPECT_TRUE(s->isSpecular()) << c.name;
        if (c.stochastic) continue;
        EXPECT_LE(s->pdf, 1.0f) << c.name;
        EXPECT_TRUE(b->f(wo, s->wi, TransportMode::Radiance).isBlack()) << c.name;
        EXPECT_EQ(b->pdf(wo, s->wi, TransportMode::Radiance), 0.0f) << c.name;
        if (s->isReflection()) { EXPECT_NEAR(length(s->wi - Vec3(-wo.x, -wo.y, wo.z)), 0, 1e-5f) << c.name; }
    }
}

// Refraction obeys Snell's law and the eta convention (eta = index below / index above).
TEST(SmoothDielectric, SnellAndEtaConvention) {
    for (float eta : {1.5f, 1 / 1.5f, 1.33f})
        for (float cosO : {0.9f, 0.3f, -0.5f, -0.99f}) {
            DielectricBxDF b(eta, tr(0));
            Vec3 wo = directionAt(cosO);
            auto s = b.sample(wo, 0.999999f, {0.5f, 0.5f}, TransportMode::Radiance);  // transmission if possible
            float nO = cosO > 0 ? 1 : eta, nI = cosO > 0 ? eta : 1;
            float sinO = std::sqrt(1 - cosO * cosO);
            if (sinO * nO / nI >= 1) {  // total internal reflection
                ASSERT_TRUE(s && s->isReflection());
                continue;
            }
            ASSERT_TRUE(s && s->isTransmission());
            float sinI = std::sqrt(std::max(0.0f, 1 - s->wi.z * s->wi.z));
            EXPECT_NEAR(nO * sinO, nI * sinI, 1e-4f);
            EXPECT_LT(s->wi.z * wo.z, 0);
            EXPECT_NEAR(s->eta, nI / nO, 1e-5f);
            EXPECT_GT(dot(Vec3(-wo.x, -wo.y, 0), Vec3(s->wi.x, s->wi.y, 0)), 0);  // continues across
        }
}

// eta = 1 passes straight through, still as one specular transmission.
TEST(SmoothDielectric, IndexOneIsPassThrough) {
    DielectricBxDF b(1.0f, tr(0.5f));
    EXPECT_EQ(b.flags(), kTransmission | kSpecular);
    Vec3 wo = normalize(Vec3(0.3f, -0.2f, 0.8f));
    auto s = b.sample(wo, 0.1f, {0.3f, 0.7f}, TransportMode::Radiance);
    ASSERT_TRUE(s);
    EXPECT_NEAR(length(s->wi + wo), 0, 1e-6f);
    EXPECT_FLOAT_EQ(s->f.g * std::fabs(s->wi.z) / s->pdf, 1.0f);
}

TEST(ThinDielectric, ReflectanceSumsInterreflections) {
    ThinDielectricBxDF b(1.5f);
    for (float cosO : {1.0f, 0.7f, 0.2f}) {
        Vec3 wo = directionAt(cosO);
        float R = fresnelDielectric(cosO, 1.5f), T = 1 - R;
        float Rp = R + T * T * R / (1 - R * R);
        auto refl = b.sample(wo, 0, {0.5f, 0.5f}, TransportMode::Radiance);
        auto trans = b.sample(wo, 0.9999f, {0.5f, 0.5f}, TransportMode::Radiance);
        ASSERT_TRUE(refl && trans);
        EXPECT_TRUE(refl->isReflection());
        EXPECT_TRUE(trans->isTransmission());
        EXPECT_NEAR(refl->pdf, Rp, 1e-5f);
        EXPECT_NEAR(trans->pdf, 1 - Rp, 1e-5f);
        EXPECT_NEAR(length(trans->wi + wo), 0, 1e-6f);
        EXPECT_NEAR(trans->f.g * std::fabs(trans->wi.z), 1 - Rp, 1e-5f);  // no eta^2 scaling
    }
    // Normal incidence at 1.5: R = 0.04, R' = 2R / (1 + R) = 0.0769...
    EXPECT_NEAR(b.sample(Vec3(0, 0, 1), 0, {0, 0}, TransportMode::Radiance)->pdf, 0.08f / 1.04f, 1e-5f);
}

TEST(Diffuse, ValueAndSide) {
    DiffuseBxDF b(Spectrum(0.2f, 0.5f, 0.8f));
    Vec3 wo(0, 0, 1), wi = normalize(Vec3(1, 1, 1));
    EXPECT_NEAR(b.f(wo, wi, TransportMode::Radiance).b, 0.8f / kPi, 1e-6f);
    EXPECT_TRUE(b.f(wo, -wi, TransportMode::Radiance).isBlack());
    EXPECT_EQ(b.flags(), kReflection | kDiffuse);
    EXPECT_EQ(DiffuseBxDF(Spectrum(0.0f)).flags(), 0);
    // Reflection is two-sided: wo below the surface reflects below.
    auto s = b.sample(-wo, 0.5f, {0.3f, 0.6f}, TransportMode::Radiance);
    ASSERT_TRUE(s);
    EXPECT_LT(s->wi.z, 0);
}

TEST(DiffuseTransmission, LobesByMaxComponent) {
    DiffuseTransmissionBxDF b(Spectrum(0.1f, 0.6f, 0.2f), Spectrum(0.2f, 0.1f, 0.3f));
    EXPECT_EQ(b.flags(), kReflection | kTransmission | kDiffuse);
    Vec3 wo(0, 0, 1);
    // P(reflect) = max(R) / (max(R) + max(T)) = 0.6 / 0.9.
    auto r = b.sample(wo, 0.6f, {0.2f, 0.2f}, TransportMode::Radiance), t = b.sample(wo, 0.7f, {0.2f, 0.2f}, TransportMode::Radiance);
    ASSERT_TRUE(r && t);
    EXPECT_TRUE(r->isReflection());
    EXPECT_GT(r->wi.z, 0);
    EXPECT_TRUE(t->isTransmission());
    EXPECT_LT(t->wi.z, 0);
    EXPECT_NEAR(r->pdf, std::fabs(r->wi.z) / kPi * (0.6f / 0.9f), 1e-6f);
    EXPECT_NEAR(t->f.b, 0.3f / kPi, 1e-6f);
}

TEST(Conductor, NormalIncidenceReflectance) {
    // F(0) = ((n-1)^2 + k^2) / ((n+1)^2 + k^2).
    ConductorBxDF b(tr(0), kCuEta, kCuK);
    auto s = b.sample(Vec3(0, 0, 1), 0.5f, {0.5f, 0.5f}, TransportMode::Radiance);
    ASSERT_TRUE(s);
    for (int c = 0; c < 3; ++c) {
        float n = kCuEta[c], k = kCuK[c];
        EXPECT_NEAR(s->f[c] * s->wi.z / s->pdf, ((n - 1) * (n - 1) + k * k) / ((n + 1) * (n + 1) + k * k), 1e-5f);
    }
    EXPECT_EQ(b.flags(), kReflection | kSpecular);
    EXPECT_EQ(ConductorBxDF(tr(0.2f), kCuEta, kCuK).flags(), kReflection | kGlossy);
}

INSTANTIATE_TEST_SUITE_P(All, Furnace, ::testing::ValuesIn(cases()), caseName);
INSTANTIATE_TEST_SUITE_P(All, Deterministic, ::testing::ValuesIn(select([](const Case& c) { return !c.smooth && !c.stochastic; })), caseName);
INSTANTIATE_TEST_SUITE_P(All, Smooth, ::testing::ValuesIn(select([](const Case& c) { return c.smooth; })), caseName);
INSTANTIATE_TEST_SUITE_P(All, Sampling, ::testing::ValuesIn(select([](const Case& c) { return c.chiSquare; })), caseName);

}  // namespace
