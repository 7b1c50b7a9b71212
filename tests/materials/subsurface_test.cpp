// The `subsurface` material's parameter forms (pbrt-v4's SubsurfaceMaterial::Create) and the
// reflectance -> albedo inversion of its "reflectance" form (beam_diffusion.h).
#include <gtest/gtest.h>

#include "materials/beam_diffusion.h"
#include "materials/create.h"
#include "materials/named_scattering.h"
#include "materials/subsurface_material.h"
#include "param_builder.h"

using namespace ps;
using namespace ps::test;

namespace {

std::shared_ptr<Material> make(const Params& p) {
    TextureRegistry reg;
    std::map<std::string, std::shared_ptr<Material>> named;
    return createMaterial("subsurface", p, reg, named, "");
}

const SubsurfaceInterior& interiorOf(const std::shared_ptr<Material>& m) {
    const auto* s = dynamic_cast<const SubsurfaceMaterial*>(m.get());
    EXPECT_NE(s, nullptr);
    return s->interior();
}

}  // namespace

// pbrt-v4's albedo for a diffuse reflectance: reference values from an independent
// transliteration (Python, double precision, pbrt-v4's FastExp and float radii emulated) of
// pbrt-v4 5f7a606's code path ComputeBeamDiffusionBSSRDF -> IntegrateCatmullRom ->
// InvertCatmullRom (bisection to 2^-200); with exact exponentials instead of FastExp the
// albedos move by at most 3e-6. Checked on 1 - rho, what sigma_a is made of.
TEST(SubsurfaceAlbedo, InvertsTheBeamDiffusionReflectanceAsPbrtV4) {
    struct Case {
        float g, eta;
        std::array<double, 5> rho;  // for reflectance 0.05, 0.2, 0.5, 0.8, 0.95
    };
    const std::array<float, 5> reflectance{0.05f, 0.2f, 0.5f, 0.8f, 0.95f};
    const Case cases[] = {
        {0.0f, 1.33f, {0.420712, 0.818249, 0.96953, 0.996581, 0.999649}},
        {0.5f, 1.33f, {0.702762, 0.927061, 0.988754, 0.99906, 0.999995}},
        {0.0f, 1.0f, {0.255222, 0.644284, 0.911816, 0.985772, 0.997151}},
        {-0.3f, 1.5f, {0.321629, 0.772961, 0.965073, 0.995452, 0.99918}},
    };
    for (const Case& c : cases) {
        const EffectiveAlbedoTable t = effectiveAlbedoTable(c.g, c.eta);
        for (int i = 0; i < 5; ++i) {
            const double rho = albedoForReflectance(t, reflectance[i]);
            std::printf("  g %.1f eta %.2f R %.2f: rho %.6f, pbrt-v4 %.6f\n", c.g, c.eta, reflectance[i], rho, c.rho[i]);
            // 1e-6 of the reference's rounding, 2e-6 of FastExp, and float sums.
            EXPECT_NEAR(rho, c.rho[i], 5e-6 + 2e-3 * (1 - c.rho[i])) << "g " << c.g << " eta " << c.eta << " R " << reflectance[i];
        }
        // The ends: no reflectance is albedo 0; the model reflects more than 1 at albedo 1
        // (1.02 for g 0, eta 1.33), so reflectance 1 is an albedo just below 1.
        EXPECT_EQ(albedoForReflectance(t, 0), 0.0f);
        EXPECT_GT(albedoForReflectance(t, 1), 0.99f);
        EXPECT_LE(albedoForReflectance(t, 1), 1.0f);
    }
}

// The material's four forms: reflectance + mfp (times scale) through the inversion, sigma_a
// + sigma_s (times scale), a measured name (g forced to 0) and pbrt-v4's default.
TEST(SubsurfaceMaterial, ParameterFormsGiveTheInteriorMedium) {
    setWarningsQuiet(true);
    {
        const auto m = make(Params().rgb("reflectance", 0.2, 0.5, 0.8).rgb("mfp", 1, 2, 4).f("scale", 0.5).f("g", 0.5));
        const SubsurfaceInterior& in = interiorOf(m);
        const EffectiveAlbedoTable t = effectiveAlbedoTable(0.5f, 1.33f);
        const float mfp[3] = {0.5f, 1, 2}, refl[3] = {0.2f, 0.5f, 0.8f};
        const Spectrum sa = in.sigmaA(nullptr), ss = in.sigmaS(nullptr);
        for (int c = 0; c < 3; ++c) {
            const float rho = albedoForReflectance(t, refl[c]);
            EXPECT_NEAR(ss[c], rho / mfp[c], 1e-6f) << c;
            EXPECT_NEAR(sa[c], (1 - rho) / mfp[c], 1e-6f) << c;
        }
        EXPECT_FLOAT_EQ(in.g, 0.5f);
        // Spectral mode: per wavelength of the lifted spectra (a grey one: the same albedo).
        const auto grey = make(Params().rgb("reflectance", 0.5, 0.5, 0.5));
        SampledWavelengths w;
        w.lambda = {420, 500, 580, 660};
        const Spectrum s = interiorOf(grey).sigmaS(&w);
        for (int i = 0; i < 4; ++i) EXPECT_NEAR(s[i], albedoForReflectance(effectiveAlbedoTable(0, 1.33f), 0.5f), 2e-4f) << i;
    }
    {
        const auto m = make(Params().rgb("sigma_a", 0.1, 0.2, 0.3).rgb("sigma_s", 1, 2, 3).f("scale", 2));
        const Spectrum sa = interiorOf(m).sigmaA(nullptr), ss = interiorOf(m).sigmaS(nullptr);
        EXPECT_FLOAT_EQ(sa.b, 0.6f);
        EXPECT_FLOAT_EQ(ss.g, 4.0f);
    }
    {
        const auto m = make(Params().s("name", "Skin1").f("g", 0.7));
        const auto skin = *namedScattering("Skin1");
        EXPECT_FLOAT_EQ(interiorOf(m).sigmaA(nullptr).b, skin.sigmaA[2]);
        EXPECT_FLOAT_EQ(interiorOf(m).sigmaS(nullptr).r, skin.sigmaS[0]);
        EXPECT_EQ(interiorOf(m).g, 0.0f);  // pbrt-v4: reduced coefficients, g = 0
    }
    {
        const auto m = make(Params());
        EXPECT_FLOAT_EQ(interiorOf(m).sigmaA(nullptr).b, 0.014f);
        EXPECT_FLOAT_EQ(interiorOf(m).sigmaS(nullptr).r, 2.55f);
    }
}
