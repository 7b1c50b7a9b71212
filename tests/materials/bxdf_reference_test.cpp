// The values of the rough BxDFs, anchored against an independent implementation of their
// models (microfacet_reference.h): for each wo, the directional albedo of each lobe from
// (a) deterministic quadrature of the reference f |cos wi|, (b) the same quadrature of the
// code's f() |cos wi| on the same nodes and (c) the code's importance sampling,
// E[f |cos wi| / pdf]. (a) = (b) pins f() pointwise in aggregate, (a) = (c) pins sample().
// The furnace tests in bxdf_test.cpp only bound the albedo; these catch a few-tenths-of-a-
// percent error in f (a missing factor, G1 for G, a wrong eta^2 scaling).
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <optional>

#include "materials/conductor_bxdf.h"
#include "materials/dielectric_bxdf.h"
#include "materials/layered_bxdf.h"
#include "microfacet_reference.h"
#include "stats.h"

using namespace ps;
using namespace ps::test;

namespace {

constexpr TransportMode kModes[2] = {TransportMode::Radiance, TransportMode::Importance};
const char* const kModeNames[2] = {"radiance", "importance"};

// Albedo per [mode][lobe], lobe 0 = reflection, 1 = transmission.
using Table = std::array<std::array<double, 2>, 2>;

struct Quadrature {
    Table ref{}, code{};
};

// Quadrature over microfacet normals of the reference and of b->f() (channel ch; none if b is
// null) for a surface with index 1 above and eta below (eta = 0: opaque, reflection only),
// whose reflectance at a microfacet is reflectance(cos(wo, m)).
Quadrature integrateAlbedo(const BxDF* b, const ref::GGX& g, Vec3 woF, double eta,
                           const std::function<double(double)>& reflectance, int ch, int n) {
    Quadrature q;
    ref::V3 wo = ref::fromVec(woF);
    double nO = wo.z > 0 ? 1 : eta, nI = wo.z > 0 ? eta : 1;
    ref::forEachNormal(g, n, n, [&](ref::V3 m, double dOmegaM) {
        ref::V3 mf = wo.z > 0 ? m : -m;  // the facet's side facing wo
        double c = ref::dot(wo, mf);
        if (c <= 0) return;
        ref::Scatter s[2] = {ref::reflectAt(g, wo, mf, reflectance(c)), eta > 0 ? ref::refractAt(g, wo, mf, nO, nI) : ref::Scatter{}};
        for (int lobe = 0; lobe < 2; ++lobe) {
            if (!s[lobe].valid) continue;
            double w = std::fabs(s[lobe].wi.z) * s[lobe].dOmegaI_dOmegaM * dOmegaM;
            Vec3 wi = ref::toVec(s[lobe].wi);
            for (int mode = 0; mode < 2; ++mode) {
                q.ref[mode][lobe] += (mode == 0 ? s[lobe].fRadiance : s[lobe].fImportance) * w;
                if (b) q.code[mode][lobe] += double(b->f(woF, wi, kModes[mode])[ch]) * w;
            }
        }
    });
    return q;
}

// E[f |cos wi| / pdf] restricted to sampled reflections (lobe 0) or transmissions (1).
MeanSE sampledAlbedo(const BxDF& b, Vec3 wo, TransportMode mode, int lobe, int ch, int n, uint64_t seed) {
    Rng rng(seed);
    return meanAndError(n, [&] {
        float uc = rng.uniform();
        Vec2 u(rng.uniform(), rng.uniform());
        auto s = b.sample(wo, uc, u, mode);
        if (!s || !(s->pdf > 0) || s->isTransmission() != (lobe == 1)) return 0.0;
        return double(s->f[ch]) * std::fabs(s->wi.z) / s->pdf;
    });
}

constexpr int kNodes = 160;  // per axis; half of it gives the quadrature error estimate
constexpr int kSamples = 100000;

// Compares (a), (b), (c) for one wo, mode, lobe and channel; returns a line for the log.
// Quadrature error: |Q(n) - Q(n/2)| (an upper bound for the midpoint rule's O(h^2) and for
// the O(h) of the lobes' cut-offs at the horizon and at total internal reflection).
void expectAgreement(const std::string& what, double ref, double refCoarse, double code, const MeanSE& sampled) {
    double quadErr = std::fabs(ref - refCoarse);
    // f() in float against the double reference on identical nodes: rounding only.
    double codeTol = 2e-4 + 2e-4 * ref;
    double sampleTol = 4 * sampled.se + quadErr + 1e-5;
    std::printf("[ albedo   ] %-50s ref %.5f (quad err %.1e) code %.5f (diff %+.1e) sampled %.5f +- %.5f (%+.1f sigma)\n",
                what.c_str(), ref, quadErr, code, code - ref, sampled.mean, sampled.se, (sampled.mean - ref) / sampled.se);
    EXPECT_NEAR(code, ref, codeTol) << what;
    EXPECT_NEAR(sampled.mean, ref, sampleTol) << what;
}

struct ConductorCase {
    std::string name;
    float ax, ay;
    Spectrum eta, k;
};

// Rough conductors: Torrance-Sparrow F D G2 / (4 |cos wo cos wi|). A perfect mirror's Fresnel
// (eta = 0, k = 1: F = 1) isolates D G2; copper adds the complex Fresnel term per channel.
TEST(ReferenceAlbedo, RoughConductor) {
    const Spectrum mirrorEta(0.0f), mirrorK(1.0f), cuEta(0.2f, 0.92f, 1.1f), cuK(3.9f, 2.45f, 2.14f);
    std::vector<ConductorCase> cases = {
        {"Mirror a=0.1", 0.1f, 0.1f, mirrorEta, mirrorK},   {"Mirror a=0.3", 0.3f, 0.3f, mirrorEta, mirrorK},
        {"Mirror a=0.7", 0.7f, 0.7f, mirrorEta, mirrorK},   {"Mirror a=(0.15,0.6)", 0.15f, 0.6f, mirrorEta, mirrorK},
        {"Copper a=0.3", 0.3f, 0.3f, cuEta, cuK},
    };
    uint64_t seed = 100;  // a new stream for every estimate: their errors are independent
    for (const ConductorCase& c : cases) {
        ConductorBxDF b(TrowbridgeReitz(c.ax, c.ay), c.eta, c.k);
        ref::GGX g{c.ax, c.ay};
        int channels = c.eta.r == c.eta.b ? 1 : 3;
        for (float cosO : {0.95f, 0.5f, 0.1f, -0.5f}) {
            Vec3 wo = directionAt(cosO, 1.1f);
            for (int ch = channels == 1 ? 1 : 0; ch < (channels == 1 ? 2 : 3); ++ch) {
                auto F = [&](double ci) { return ref::fresnelConductor(ci, c.eta[ch], c.k[ch]); };
                Quadrature fine = integrateAlbedo(&b, g, wo, 0, F, ch, kNodes);
                Quadrature coarse = integrateAlbedo(&b, g, wo, 0, F, ch, kNodes / 2);
                MeanSE m = sampledAlbedo(b, wo, TransportMode::Importance, 0, ch, kSamples, ++seed);
                char what[128];
                std::snprintf(what, sizeof what, "%s cos(wo)=%5.2f ch%d", c.name.c_str(), cosO, ch);
                expectAgreement(what, fine.ref[1][0], coarse.ref[1][0], fine.code[1][0], m);
                // f() does not depend on the mode.
                EXPECT_DOUBLE_EQ(fine.code[0][0], fine.code[1][0]) << what;
            }
        }
    }
}

// Rough dielectrics (Walter et al. 2007): reflection and transmission separately, entering
// (wo above) and leaving (wo below), in radiance mode (transmission scaled by 1/eta'^2) and
// importance mode (its adjoint, unscaled).
TEST(ReferenceAlbedo, RoughDielectric) {
    struct Case {
        std::string name;
        float eta, ax, ay;
    };
    std::vector<Case> cases = {
        {"eta=1.5 a=0.1", 1.5f, 0.1f, 0.1f},
        {"eta=1.5 a=0.4", 1.5f, 0.4f, 0.4f},
        {"eta=1/1.5 a=0.3", 1 / 1.5f, 0.3f, 0.3f},
        {"eta=1.33 a=(0.1,0.5)", 1.33f, 0.1f, 0.5f},
    };
    uint64_t seed = 200;
    for (const Case& c : cases) {
        DielectricBxDF b(c.eta, TrowbridgeReitz(c.ax, c.ay));
        ref::GGX g{c.ax, c.ay};
        for (float cosO : {0.9f, 0.4f, -0.4f, -0.9f}) {
            Vec3 wo = directionAt(cosO, 1.1f);
            double nO = cosO > 0 ? 1 : c.eta, nI = cosO > 0 ? c.eta : 1;
            auto F = [&](double ci) { return ref::fresnelDielectric(ci, nO, nI); };
            Quadrature fine = integrateAlbedo(&b, g, wo, c.eta, F, 1, kNodes);
            Quadrature coarse = integrateAlbedo(&b, g, wo, c.eta, F, 1, kNodes / 2);
            for (int mode = 0; mode < 2; ++mode)
                for (int lobe = 0; lobe < 2; ++lobe) {
                    MeanSE m = sampledAlbedo(b, wo, kModes[mode], lobe, 1, kSamples, ++seed);
                    char what[128];
                    std::snprintf(what, sizeof what, "%s cos(wo)=%5.2f %s %s", c.name.c_str(), cosO,
                                  lobe ? "T" : "R", kModeNames[mode]);
                    expectAgreement(what, fine.ref[mode][lobe], coarse.ref[mode][lobe], fine.code[mode][lobe], m);
                }
        }
    }
}

// ---- Coated diffuse (smooth or rough dielectric over a Lambertian base R, slab of optical
// thickness t that absorbs but does not scatter). Light leaving the base is cosine-
// distributed whatever its history, so the walk reduces to a geometric series:
//   albedo(wo) = R_top(wo) + T_top(wo) a(wo) R esc / (1 - R ret),
//   esc = integral 2 mu a(mu) T_in(mu) dmu,  ret = integral 2 mu a(mu)^2 R_in(mu) dmu,
// with a(mu) = exp(-t / mu) the slab's transmittance along cosine mu, R_in and T_in the
// coating's albedos for light arriving from inside at cosine mu and a(wo) along the
// refracted wo. Smooth: Fresnel for R and T. Rough: only t = 0, where the directions inside
// do not matter, with the reference rough-dielectric albedos above.

LayerParams slab(float thickness) {
    LayerParams p;
    p.thickness = thickness;
    p.albedo = Spectrum(0.0f);
    p.maxDepth = 200;  // the series must not be truncated (Russian roulette keeps it cheap)
    return p;
}

double smoothCoatedDiffuseAlbedo(double cosO, double eta, double R, double t) {
    const int n = 20000;
    double esc = 0, ret = 0;
    for (int i = 0; i < n; ++i) {
        double mu = (i + 0.5) / n, a = std::exp(-t / mu), Fin = ref::fresnelDielectric(mu, eta, 1);
        esc += 2 * mu * a * (1 - Fin) / n;
        ret += 2 * mu * a * a * Fin / n;
    }
    double F = ref::fresnelDielectric(cosO, 1, eta);
    double muT = std::sqrt(1 - (1 - cosO * cosO) / (eta * eta));
    return F + (1 - F) * std::exp(-t / muT) * R * esc / (1 - R * ret);
}

// Rough coating at t = 0, from reference importance-mode albedos of the coating: esc and
// ret from nMu cosines inside (nodes x nodes microfacet normals each), then per wo.
struct RoughCoating {
    double eta, esc = 0, ret = 0;
    ref::GGX g;
    int nodes;
    std::array<double, 2> albedos(double c) const {  // {R, T} for wo at cosine c
        double nO = c > 0 ? 1 : eta, nI = c > 0 ? eta : 1;
        auto F = [&](double ci) { return ref::fresnelDielectric(ci, nO, nI); };
        return integrateAlbedo(nullptr, g, directionAt(float(c)), eta, F, 1, nodes).ref[1];
    }
    RoughCoating(double eta, double alpha, int nMu, int nodes) : eta(eta), g{alpha, alpha}, nodes(nodes) {
        for (int i = 0; i < nMu; ++i) {
            double mu = (i + 0.5) / nMu;
            std::array<double, 2> in = albedos(-mu);  // arriving from inside: wo points down into the slab
            esc += 2 * mu * in[1] / nMu;
            ret += 2 * mu * in[0] / nMu;
        }
    }
    double albedo(double cosO, double R) const {
        std::array<double, 2> top = albedos(cosO);
        return top[0] + top[1] * R * esc / (1 - R * ret);
    }
};

TEST(ReferenceAlbedo, CoatedDiffuse) {
    struct Case {
        std::string name;
        float alpha, R, thickness;
    };
    const float eta = 1.5f;
    std::vector<Case> cases = {
        {"smooth R=0.5 t=0", 0, 0.5f, 0},
        {"smooth R=0.7 t=0.5", 0, 0.7f, 0.5f},
        {"rough a=0.3 R=0.8 t=0", 0.3f, 0.8f, 0},
    };
    uint64_t seed = 300;
    for (const Case& c : cases) {
        CoatedDiffuseBxDF b(DielectricBxDF(eta, TrowbridgeReitz(c.alpha, c.alpha)), DiffuseBxDF(Spectrum(c.R)), slab(c.thickness));
        std::optional<RoughCoating> fine, coarse;
        if (c.alpha > 0) fine.emplace(eta, c.alpha, 48, 128), coarse.emplace(eta, c.alpha, 24, 64);
        for (float cosO : {0.9f, 0.3f, -0.6f}) {  // two-sided: below is the mirror image
            double mu = std::fabs(cosO), ref, refErr;
            if (c.alpha == 0) {
                ref = smoothCoatedDiffuseAlbedo(mu, eta, c.R, c.thickness);
                refErr = 1e-5;
            } else {
                ref = fine->albedo(mu, c.R);
                refErr = std::fabs(ref - coarse->albedo(mu, c.R));
            }
            for (int mode = 0; mode < 2; ++mode) {
                if (mode == 0 && cosO != 0.9f) continue;  // radiance mode: entering and leaving scalings cancel
                MeanSE m = furnace(b, directionAt(cosO, 1.1f), kModes[mode], 100000, ++seed);
                std::printf("[ albedo   ] coated diffuse %-24s cos(wo)=%5.2f %-10s ref %.5f (err %.1e) sampled %.5f +- %.5f (%+.1f sigma)\n",
                            c.name.c_str(), cosO, kModeNames[mode], ref, refErr, m.mean, m.se, (m.mean - ref) / m.se);
                EXPECT_NEAR(m.mean, ref, 4 * m.se + refErr) << c.name << " cos(wo)=" << cosO << " " << kModeNames[mode];
            }
        }
    }
}

}  // namespace
