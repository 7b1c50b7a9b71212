// The hair BSDF (pbrt-v4's model): energy conservation without absorption by uniform
// sampling (an estimate that does not use the BSDF's own sampling), agreement of its
// importance sampling with uniform sampling under absorption in both transport modes,
// sample/pdf consistency, the adjoint, chi-square of sampled directions against pdf() and
// the pdf's integral, the Bessel function it rests on, and the material's parameters
// (pbrt-v4's precedence, defaults and h = -1 + 2 v). Fixed seeds throughout.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>

#include "materials/create.h"
#include "materials/hair_bxdf.h"
#include "math/bessel.h"
#include "math/warp.h"
#include "mc/rng.h"
#include "param_builder.h"
#include "stats.h"

using namespace ps;
using namespace ps::test;

namespace {

struct Config {
    float sinThetaO, phiO, h, betaM, betaN, alpha;
};

// wo from its angle to the fibre (x) and its azimuth around it (from y towards z).
Vec3 hairDirection(float sinTheta, float phi) {
    float c = std::sqrt(std::max(0.0f, 1 - sinTheta * sinTheta));
    return Vec3(sinTheta, c * std::cos(phi), c * std::sin(phi));
}

HairBxDF make(const Config& c, Spectrum sigmaA) {
    HairParams p;
    p.h = c.h;
    p.betaM = c.betaM;
    p.betaN = c.betaN;
    p.alphaDegrees = c.alpha;
    p.sigmaA = sigmaA;
    return HairBxDF(p);
}

// Spread over incidence, offset and both roughnesses (the narrow-lobe branch of Mp, v <= 0.1,
// is taken by beta_m <= 0.33; beta_m = 0.2 gives lobe variances 0.008 .. 0.13).
const Config kConfigs[] = {
    {0.0f, 1.2f, 0.0f, 0.3f, 0.3f, 2},     {0.5f, -2.0f, 0.5f, 0.3f, 0.3f, 2},  {-0.7f, 0.4f, -0.8f, 0.2f, 0.5f, 3},
    {0.9f, 2.8f, 0.95f, 0.5f, 0.2f, -2},   {-0.2f, -0.9f, -0.3f, 0.8f, 0.8f, 0}, {0.3f, 0.0f, 0.99f, 1.0f, 1.0f, 5},
    {0.6f, -1.6f, -0.6f, 0.25f, 0.25f, 10},
};

// E[4 pi f(wo, wi) |cos wi|] over uniform directions, per channel, with standard errors.
struct Channels {
    double mean[3] = {0, 0, 0}, se[3] = {0, 0, 0};
};
template <typename Sample>
Channels estimate(int n, Sample next) {
    double sum[3] = {0, 0, 0}, sum2[3] = {0, 0, 0};
    for (int i = 0; i < n; ++i) {
        Spectrum v = next();
        for (int c = 0; c < 3; ++c) {
            sum[c] += v[c];
            sum2[c] += double(v[c]) * v[c];
        }
    }
    Channels r;
    for (int c = 0; c < 3; ++c) {
        r.mean[c] = sum[c] / n;
        r.se[c] = std::sqrt(std::max(0.0, sum2[c] / n - r.mean[c] * r.mean[c]) / (n - 1));
    }
    return r;
}

Channels uniformAlbedo(const HairBxDF& b, Vec3 wo, TransportMode mode, int n, uint64_t seed) {
    Rng rng(seed);
    return estimate(n, [&] {
        Vec3 wi = sampleUniformSphere({rng.uniform(), rng.uniform()});
        return b.f(wo, wi, mode) * (std::fabs(wi.z) * 4 * kPi);
    });
}

Channels sampledAlbedo(const HairBxDF& b, Vec3 wo, TransportMode mode, int n, uint64_t seed) {
    Rng rng(seed);
    return estimate(n, [&] {
        float uc = rng.uniform();
        Vec2 u(rng.uniform(), rng.uniform());
        auto s = b.sample(wo, uc, u, mode);
        if (!s || !(s->pdf > 0)) return Spectrum();
        return s->f * (std::fabs(s->wi.z) / s->pdf);
    });
}

}  // namespace

// I0 against the C++ library's cyl_bessel_i, and log I0 continuous where its branches meet.
TEST(HairBessel, MatchesTheLibrary) {
    double worst = 0;
    for (double x : {0.0, 0.1, 1.0, 5.0, 9.9, 12.0, 20.0, 29.9, 30.0, 50.0, 120.0, 400.0, 700.0}) {
        double ref = std::cyl_bessel_i(0.0, x);
        worst = std::max(worst, std::fabs(besselI0(x) / ref - 1));
        EXPECT_NEAR(besselI0(x) / ref, 1, 1e-13) << x;
        EXPECT_NEAR(logBesselI0(x), std::log(ref), 1e-9 * std::max(1.0, x)) << x;
    }
    std::printf("  largest relative error of I0 %.2g\n", worst);
    EXPECT_NEAR(logBesselI0(30 - 1e-9), logBesselI0(30), 1e-8);
}

// sigma_a = 0: every lobe's Mp and Np are normalised and the Ap sum to 1, so the integral
// of f |cos wi| over the sphere is 1 for every wo, h and roughness. Estimated with uniform
// directions (independent of the BSDF's sampling); importance sampling gives weights of
// exactly 1, checked too.
TEST(Hair, WhiteFurnace) {
    const int n = 300000;
    for (const Config& c : kConfigs) {
        HairBxDF b = make(c, Spectrum(0.0f));
        Vec3 wo = hairDirection(c.sinThetaO, c.phiO);
        Channels u = uniformAlbedo(b, wo, TransportMode::Radiance, n, 11);
        Channels s = sampledAlbedo(b, wo, TransportMode::Radiance, 20000, 12);
        std::printf("[ furnace ] sin(theta_o)=%5.2f h=%5.2f beta_m=%.2f beta_n=%.2f alpha=%3.0f: uniform %.4f ± %.4f (%.1f sigma), sampled %.6f ± %.1g\n",
                    c.sinThetaO, c.h, c.betaM, c.betaN, c.alpha, u.mean[1], u.se[1], (u.mean[1] - 1) / u.se[1], s.mean[1], s.se[1]);
        EXPECT_NEAR(u.mean[1], 1, 4 * u.se[1]) << c.sinThetaO << " " << c.h;
        EXPECT_LT(u.se[1], 0.02);  // a test that can see a few percent
        EXPECT_NEAR(s.mean[1], 1, 1e-4 + 4 * s.se[1]);
    }
}

// With coloured absorption the lobe choice no longer matches Ap, and in importance mode f is
// the adjoint: E[f |cos| / pdf] from the BSDF's samples equals the uniform estimate of the
// same integral, per channel and in both modes, within 4 sigma of the difference.
TEST(Hair, ImportanceSamplingMatchesUniform) {
    const Spectrum sigma(0.15f, 0.6f, 2.5f);
    int i = 0;
    for (const Config& c : kConfigs) {
        HairBxDF b = make(c, sigma);
        Vec3 wo = hairDirection(c.sinThetaO, c.phiO);
        for (TransportMode mode : {TransportMode::Radiance, TransportMode::Importance}) {
            ++i;
            Channels u = uniformAlbedo(b, wo, mode, 150000, 100 + i);
            Channels s = sampledAlbedo(b, wo, mode, 60000, 200 + i);
            for (int ch = 0; ch < 3; ++ch) {
                double sd = std::sqrt(u.se[ch] * u.se[ch] + s.se[ch] * s.se[ch]);
                EXPECT_NEAR(s.mean[ch], u.mean[ch], 4 * sd) << "config " << i << " channel " << ch;
            }
            std::printf("[ albedo  ] %s sin(theta_o)=%5.2f h=%5.2f: sampled %.4f %.4f %.4f, uniform %.4f %.4f %.4f (green diff %.1f sigma)\n",
                        mode == TransportMode::Radiance ? "radiance  " : "importance", c.sinThetaO, c.h, s.mean[0], s.mean[1], s.mean[2],
                        u.mean[0], u.mean[1], u.mean[2],
                        (s.mean[1] - u.mean[1]) / std::sqrt(u.se[1] * u.se[1] + s.se[1] * s.se[1]));
            if (mode == TransportMode::Radiance) {
                for (int ch = 0; ch < 3; ++ch) EXPECT_LT(s.mean[ch], 1);
            }
        }
    }
}

// A sample's f and pdf are f() and pdf() at its direction, in both modes (importance mode
// samples the mirrored azimuth: its pdf is the radiance pdf of the mirrored direction).
TEST(Hair, SampleMatchesEvaluation) {
    Rng rng(7);
    int checked = 0;
    for (const Config& c : kConfigs) {
        HairBxDF b = make(c, Spectrum(0.3f, 0.5f, 0.9f));
        for (TransportMode mode : {TransportMode::Radiance, TransportMode::Importance})
            for (int i = 0; i < 3000; ++i) {
                Vec3 wo = sampleUniformSphere({rng.uniform(), rng.uniform()});
                float uc = rng.uniform();
                Vec2 u(rng.uniform(), rng.uniform());
                auto s = b.sample(wo, uc, u, mode);
                ASSERT_TRUE(s);
                ++checked;
                EXPECT_EQ(s->flags, kReflection | kGlossy);
                EXPECT_EQ(s->eta, 1);
                ASSERT_NEAR(length(s->wi), 1, 1e-5f);
                float pdf = b.pdf(wo, s->wi, mode);
                ASSERT_NEAR(pdf, s->pdf, 2e-3f * std::max(1.0f, s->pdf));

                Spectrum f = b.f(wo, s->wi, mode);
                for (int ch = 0; ch < 3; ++ch) ASSERT_NEAR(f[ch], s->f[ch], 2e-3f * std::max(1.0f, s->f[ch]));
            }
    }
    EXPECT_EQ(checked, 2 * 3000 * int(std::size(kConfigs)));
}

// Importance mode is the adjoint f*(wo, wi) = f(wi, wo). The model is not reciprocal, so
// this differs from f(wo, wi): measured here, or the test could not tell the two apart.
TEST(Hair, ImportanceModeIsTheAdjoint) {
    HairBxDF b = make(kConfigs[1], Spectrum(0.2f, 0.4f, 0.8f));
    Rng rng(9);
    double largestAsymmetry = 0;
    for (int i = 0; i < 20000; ++i) {
        Vec3 wo = sampleUniformSphere({rng.uniform(), rng.uniform()});
        Vec3 wi = sampleUniformSphere({rng.uniform(), rng.uniform()});
        Spectrum fi = b.f(wo, wi, TransportMode::Importance), rr = b.f(wi, wo, TransportMode::Radiance);
        Spectrum fr = b.f(wo, wi, TransportMode::Radiance);
        for (int ch = 0; ch < 3; ++ch) {
            ASSERT_EQ(fi[ch], rr[ch]);
            ASSERT_GE(fr[ch], 0);
            if (fr[ch] + rr[ch] > 0.05f) largestAsymmetry = std::max(largestAsymmetry, std::fabs(double(fr[ch] - rr[ch])) / (fr[ch] + rr[ch]));
        }
    }
    std::printf("  largest |f(wo,wi) - f(wi,wo)| / (f(wo,wi) + f(wi,wo)): %.3f\n", largestAsymmetry);
    EXPECT_GT(largestAsymmetry, 0.1);
}

// Pearson's chi-square of sampled directions against pdf() over a 20 x 40 (theta, phi)
// grid of the sphere; the same quadrature of pdf() must integrate to 1 (sampling never fails).
TEST(Hair, ChiSquareAgainstPdf) {
    const double alphaLevel = sidak(1e-3, 8);
    const SphereGrid grid(20, 40);
    const int n = 150000;
    for (int run = 0; run < 8; ++run) {
        const int k = std::array<int, 4>{0, 2, 3, 6}[run / 2];
        const TransportMode mode = run % 2 ? TransportMode::Importance : TransportMode::Radiance;
        const Config& c = kConfigs[k];
        HairBxDF b = make(c, Spectrum(0.2f, 0.5f, 1.2f));
        Vec3 wo = hairDirection(c.sinThetaO, c.phiO);
        std::vector<double> expected = grid.integrate([&](Vec3 wi) { return b.pdf(wo, wi, mode); }, 24);
        double total = 0;
        for (double e : expected) total += e;
        std::vector<double> observed(expected.size(), 0.0);
        Rng rng(300 + run);
        int ok = 0;
        for (int i = 0; i < n; ++i) {
            float uc = rng.uniform();
            Vec2 u(rng.uniform(), rng.uniform());
            if (auto s = b.sample(wo, uc, u, mode)) {
                observed[grid.cellOf(s->wi)] += 1;
                ++ok;
            }
        }
        EXPECT_EQ(ok, n);
        EXPECT_NEAR(total, 1, 3e-3) << "config " << k;
        for (double& e : expected) e *= ok / total;
        ChiSquareResult r = chiSquare(observed, expected);
        std::printf("[ chi2    ] %s config %d (beta_m %.2f, beta_n %.2f, h %5.2f): chi2=%7.1f dof=%3d p=%.3g; integral of pdf %.5f\n",
                    run % 2 ? "importance" : "radiance  ", k, c.betaM, c.betaN, c.h, r.chi2, r.dof, r.pValue, total);
        EXPECT_GT(r.pValue, alphaLevel) << "config " << k;
    }
}

// Values at the edges of the parameters stay finite: h = +-1, fibre-aligned directions,
// infinite absorption (a black reflectance), indices below 1, the smallest roughness.
TEST(Hair, FiniteAtTheEdges) {
    Rng rng(13);
    int n = 0;
    for (float h : {-1.0f, 0.0f, 1.0f})
        for (float eta : {0.5f, 1.0f, 1.55f})
            for (float beta : {0.01f, 1.0f})
                for (Spectrum sigma : {Spectrum(0.0f), Spectrum(1e30f), HairBxDF::sigmaAFromReflectance(Spectrum(0.0f), beta)}) {
                    HairParams p;
                    p.h = h;
                    p.eta = eta;
                    p.betaM = p.betaN = beta;
                    p.sigmaA = sigma;
                    HairBxDF b(p);
                    for (int i = 0; i < 200; ++i) {
                        Vec3 wo = i == 0 ? Vec3(1, 0, 0) : i == 1 ? Vec3(0, 0, 1) : sampleUniformSphere({rng.uniform(), rng.uniform()});
                        Vec3 wi = i == 2 ? Vec3(-1, 0, 0) : sampleUniformSphere({rng.uniform(), rng.uniform()});
                        ASSERT_TRUE(b.f(wo, wi, TransportMode::Radiance).isFinite()) << h << " " << eta << " " << beta;
                        ASSERT_TRUE(std::isfinite(b.pdf(wo, wi, TransportMode::Radiance)));
                        auto s = b.sample(wo, rng.uniform(), {rng.uniform(), rng.uniform()}, TransportMode::Importance);
                        if (s) { ASSERT_TRUE(s->f.isFinite() && std::isfinite(s->pdf) && isFinite(s->wi)); }
                        ++n;
                    }
                }
    EXPECT_EQ(n, 3 * 3 * 2 * 3 * 200);
}

namespace {

class HairMaterialTest : public ::testing::Test {
protected:
    void SetUp() override {
        setWarningsQuiet(true);
        ctx_.uv = Vec2(0.3f, 0.8f);  // h = 0.6
        ctx_.n = Vec3(0, 0, 1);
    }
    const BxDF* bxdf(const Params& p) {
        auto m = createMaterial("hair", p, reg_, named_, "");
        return m->bxdf(ctx_, scratch_);
    }
    // Same f as the BxDF with these parameters, at a spread of directions.
    void expectSameAs(const BxDF* b, HairParams p) {
        HairBxDF ref(p);
        Rng rng(5);
        for (int i = 0; i < 50; ++i) {
            Vec3 wo = sampleUniformSphere({rng.uniform(), rng.uniform()});
            Vec3 wi = sampleUniformSphere({rng.uniform(), rng.uniform()});
            Spectrum a = b->f(wo, wi, TransportMode::Radiance), r = ref.f(wo, wi, TransportMode::Radiance);
            for (int ch = 0; ch < 3; ++ch) ASSERT_NEAR(a[ch], r[ch], 1e-5f * std::max(1.0f, r[ch])) << i;
        }
    }
    HairParams expected(Spectrum sigma) {
        HairParams p;
        p.h = 0.6f;
        p.sigmaA = sigma;
        return p;
    }
    TextureRegistry reg_;
    std::map<std::string, std::shared_ptr<Material>> named_;
    MaterialEvalContext ctx_;
    ScratchBuffer scratch_;
};

}  // namespace

// pbrt-v4's constants: melanin absorption in RGB and the reflectance fit.
TEST(Hair, AbsorptionConversions) {
    Spectrum s = HairBxDF::sigmaAFromConcentration(1.3f, 0.5f);
    EXPECT_NEAR(s.r, 1.3 * 0.419 + 0.5 * 0.187, 1e-6);
    EXPECT_NEAR(s.g, 1.3 * 0.697 + 0.5 * 0.4, 1e-6);
    EXPECT_NEAR(s.b, 1.3 * 1.37 + 0.5 * 1.05, 1e-6);
    // (ln c / (5.969 - 0.215 b + 2.532 b^2 - 10.73 b^3 + 5.574 b^4 + 0.245 b^5))^2, at a
    // beta_n where every coefficient matters.
    for (double b : {0.3, 0.9}) {
        Spectrum r = HairBxDF::sigmaAFromReflectance(Spectrum(0.5f, 0.25f, 1.0f), float(b));
        const double d = 5.969 - 0.215 * b + 2.532 * b * b - 10.73 * b * b * b + 5.574 * b * b * b * b + 0.245 * b * b * b * b * b;
        const double er = std::pow(std::log(0.5) / d, 2), eg = std::pow(std::log(0.25) / d, 2);
        EXPECT_NEAR(r.r, er, 1e-5 * er) << b;
        EXPECT_NEAR(r.g, eg, 1e-5 * eg) << b;
        EXPECT_EQ(r.b, 0);
    }
}

TEST_F(HairMaterialTest, DefaultsAndPrecedence) {
    int before = warningCount();
    // Nothing given: eumelanin 1.3, eta 1.55, beta_m = beta_n = 0.3, alpha 2.
    expectSameAs(bxdf(Params()), expected(HairBxDF::sigmaAFromConcentration(1.3f, 0)));
    // Melanin: an absent concentration counts as 0.
    expectSameAs(bxdf(Params().f("pheomelanin", 2)), expected(HairBxDF::sigmaAFromConcentration(0, 2)));
    expectSameAs(bxdf(Params().f("eumelanin", 0.5).f("pheomelanin", 0.25)), expected(HairBxDF::sigmaAFromConcentration(0.5f, 0.25f)));
    // reflectance (or its alias color) goes through the fit with the (clamped) beta_n.
    HairParams p = expected(HairBxDF::sigmaAFromReflectance(Spectrum(0.4f, 0.3f, 0.2f), 0.3f));
    expectSameAs(bxdf(Params().rgb("reflectance", 0.4, 0.3, 0.2)), p);
    expectSameAs(bxdf(Params().rgb("color", 0.4, 0.3, 0.2)), p);
    p = expected(HairBxDF::sigmaAFromReflectance(Spectrum(0.4f, 0.3f, 0.2f), 1.0f));
    p.betaN = 1;
    expectSameAs(bxdf(Params().rgb("reflectance", 0.4, 0.3, 0.2).f("beta_n", 3)), p);
    EXPECT_EQ(warningCount(), before);
    // sigma_a wins over the others, reflectance over melanin, each with a warning.
    expectSameAs(bxdf(Params().rgb("sigma_a", 0.1, 0.2, 3).rgb("reflectance", 0.5, 0.5, 0.5).f("eumelanin", 3)),
                 expected(Spectrum(0.1f, 0.2f, 3)));
    EXPECT_EQ(warningCount(), before + 2);
    expectSameAs(bxdf(Params().rgb("reflectance", 0.4, 0.3, 0.2).f("eumelanin", 3).f("pheomelanin", 1)),
                 expected(HairBxDF::sigmaAFromReflectance(Spectrum(0.4f, 0.3f, 0.2f), 0.3f)));
    EXPECT_EQ(warningCount(), before + 4);
    // The other parameters, with pbrt-v4's clamp of beta_m to [0.01, 1].
    HairParams q = expected(Spectrum(0.5f));
    q.eta = 1.4f;
    q.betaM = 0.01f;
    q.betaN = 0.7f;
    q.alphaDegrees = -3;
    expectSameAs(bxdf(Params().rgb("sigma_a", 0.5, 0.5, 0.5).f("eta", 1.4).f("beta_m", 0).f("beta_n", 0.7).f("alpha", -3)), q);
    EXPECT_EQ(warningCount(), before + 4);
}

// h = -1 + 2 v from the hit's surface parameters, clamped to the fibre.
TEST_F(HairMaterialTest, OffsetFromV) {
    for (float v : {0.0f, 0.25f, 0.5f, 0.9f, 1.0f, 1.5f}) {
        ctx_.uv = Vec2(0.7f, v);
        HairParams p = expected(Spectrum(0.5f));
        p.h = std::clamp(-1 + 2 * v, -1.0f, 1.0f);
        expectSameAs(bxdf(Params().rgb("sigma_a", 0.5, 0.5, 0.5)), p);
    }
}
