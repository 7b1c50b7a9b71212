// Materials from parameter lists: defaults, textured parameters, the conductor's two
// forms, dielectric eta forms, roughness conventions, layered materials, mix, interface,
// and warnings for what is unknown.
#include <gtest/gtest.h>

#include "materials/conductor_bxdf.h"
#include "materials/create.h"
#include "materials/dielectric_bxdf.h"
#include "materials/fresnel.h"
#include "materials/textures.h"
#include "mc/rng.h"
#include "param_builder.h"
#include "scene/spectra.h"

using namespace ps;
using namespace ps::test;

namespace {

class Materials : public ::testing::Test {
protected:
    void SetUp() override {
        setWarningsQuiet(true);
        ctx_.p = Vec3(0.1f, 0.2f, 0.3f);
        ctx_.n = Vec3(0, 0, 1);
        ctx_.uv = Vec2(0.5f, 0.5f);
        ctx_.wo = Vec3(0, 0, 1);
        ctx_.dpdu = Vec3(1, 0, 0);
    }
    std::shared_ptr<Material> make(const std::string& type, const Params& p) { return createMaterial(type, p, reg_, named_, ""); }
    const BxDF* bxdf(const Material& m) { return m.resolve(ctx_)->bxdf(ctx_, scratch_); }
    // Albedo for normal incidence from the BxDF's own sampling (specular lobes included).
    float albedo(const BxDF& b, int channel = 1, Vec3 wo = Vec3(0, 0, 1)) {
        Rng rng(3);
        double sum = 0;
        const int n = 20000;
        for (int i = 0; i < n; ++i) {
            float uc = rng.uniform();
            Vec2 u(rng.uniform(), rng.uniform());
            auto s = b.sample(wo, uc, u, TransportMode::Radiance);
            if (s && s->pdf > 0) sum += s->f[channel] * std::fabs(s->wi.z) / s->pdf;
        }
        return float(sum / n);
    }
    TextureRegistry reg_;
    std::map<std::string, std::shared_ptr<Material>> named_;
    MaterialEvalContext ctx_;
    ScratchBuffer scratch_;
};

const Vec3 kUp(0, 0, 1), kOblique = normalize(Vec3(0.3f, 0.1f, 0.9f));

TEST_F(Materials, DiffuseDefaultsAndTextures) {
    auto m = make("diffuse", Params());
    EXPECT_NEAR(bxdf(*m)->f(kUp, kOblique, TransportMode::Radiance).g, 0.5f / kPi, 1e-6f);
    auto rgb = make("diffuse", Params().rgb("reflectance", 0.2, 0.4, 0.6));
    EXPECT_NEAR(bxdf(*rgb)->f(kUp, kOblique, TransportMode::Radiance).b, 0.6f / kPi, 1e-6f);
    // A textured reflectance is evaluated at the shading point and clamped to [0, 1].
    reg_.spectra["bright"] = std::make_shared<ConstantTexture<Spectrum>>(Spectrum(1.5f, 0.5f, -0.2f));
    auto tex = make("diffuse", Params().tex("reflectance", "bright"));
    Spectrum f = bxdf(*tex)->f(kUp, kOblique, TransportMode::Radiance);
    EXPECT_NEAR(f.r, 1 / kPi, 1e-6f);
    EXPECT_NEAR(f.g, 0.5f / kPi, 1e-6f);
    EXPECT_EQ(f.b, 0);
    EXPECT_THROW(make("diffuse", Params().tex("reflectance", "nope")), InputError);
    EXPECT_THROW(make("diffuse", Params().rgb("reflectance", 1.2, 0, 0)), InputError);  // albedo > 1, as pbrt-v4
}

// A constant reflectance gives one BxDF built with the material, equal to the per-point one;
// a varying texture gives none.
TEST_F(Materials, ConstantDiffuseBxDFIsBuiltOnce) {
    reg_.spectra["bright"] = std::make_shared<ConstantTexture<Spectrum>>(Spectrum(1.5f, 0.5f, 0.2f));
    auto constant = make("diffuse", Params().tex("reflectance", "bright"));
    ASSERT_NE(constant->constantBxDF(), nullptr);
    for (Vec3 wi : {kOblique, Vec3(0, 0.6f, 0.8f)}) {
        Spectrum a = constant->constantBxDF()->f(kUp, wi, TransportMode::Radiance);
        Spectrum b = bxdf(*constant)->f(kUp, wi, TransportMode::Radiance);
        for (int c = 0; c < 3; ++c) EXPECT_EQ(a[c], b[c]);
    }
    reg_.spectra["scaled"] = std::make_shared<ScaleTexture<Spectrum>>(reg_.spectra["bright"],
                                                                       std::make_shared<ConstantTexture<float>>(0.5f));
    EXPECT_EQ(make("diffuse", Params().tex("reflectance", "scaled"))->constantBxDF(), nullptr);
    EXPECT_EQ(make("conductor", Params())->constantBxDF(), nullptr);  // not built once (yet)
}

TEST_F(Materials, ConductorForms) {
    // Default: copper, smooth.
    const BxDF* cu = bxdf(*make("conductor", Params()));
    EXPECT_EQ(cu->flags(), kReflection | kSpecular);
    float r = albedo(*cu, 0), g = albedo(*cu, 1), b = albedo(*cu, 2);
    EXPECT_GT(r, g);
    EXPECT_GT(g, b);
    EXPECT_NEAR(r, 0.95f, 0.03f);
    // reflectance form: eta = 1, k chosen so that normal incidence reflects r.
    const BxDF* refl = bxdf(*make("conductor", Params().rgb("reflectance", 0.3, 0.6, 0.9)));
    EXPECT_NEAR(albedo(*refl, 0), 0.3f, 1e-4f);
    EXPECT_NEAR(albedo(*refl, 2), 0.9f, 1e-4f);
    // Named spectra for eta and k.
    const BxDF* au = bxdf(*make("conductor", Params().namedSpectrum("eta", "metal-Au-eta").namedSpectrum("k", "metal-Au-k")));
    EXPECT_GT(albedo(*au, 0), albedo(*au, 2));
    // Both forms: an error, as in pbrt-v4.
    EXPECT_THROW(make("conductor", Params().rgb("reflectance", 0.5, 0.5, 0.5).rgb("eta", 1, 1, 1)), InputError);
    // "float eta" is not a spectrum: left unused and reported.
    int before = warningCount();
    make("conductor", Params().f("eta", 1.5));
    EXPECT_EQ(warningCount(), before + 1);
}

TEST_F(Materials, Roughness) {
    // roughness 0.01 -> alpha 0.1 (remapped): glossy; without remapping alpha 0.01, still glossy.
    EXPECT_EQ(bxdf(*make("conductor", Params().f("roughness", 0.01)))->flags(), kReflection | kGlossy);
    EXPECT_EQ(bxdf(*make("conductor", Params().f("roughness", 0.01).b("remaproughness", false)))->flags(), kReflection | kGlossy);
    // roughness 1e-7 -> alpha 3e-4 < 1e-3: perfectly specular.
    EXPECT_EQ(bxdf(*make("conductor", Params().f("roughness", 1e-7)))->flags(), kReflection | kSpecular);
    // uroughness / vroughness override roughness: compare with a direct anisotropic BxDF.
    const BxDF* aniso = bxdf(*make("conductor", Params().f("roughness", 0.5).f("uroughness", 0.04).f("vroughness", 0.25)));
    ConductorBxDF ref(TrowbridgeReitz(0.2f, 0.5f), *namedSpectrumToRGB("metal-Cu-eta", SpectrumKind::Unbounded), *namedSpectrumToRGB("metal-Cu-k", SpectrumKind::Unbounded));
    Vec3 wi = normalize(Vec3(-0.4f, 0.3f, 0.8f));
    EXPECT_NEAR(aniso->f(kOblique, wi, TransportMode::Radiance).g, ref.f(kOblique, wi, TransportMode::Radiance).g, 1e-5f);
    // Textured roughness.
    reg_.floats["rough"] = std::make_shared<ConstantTexture<float>>(0.25f);
    const BxDF* tex = bxdf(*make("dielectric", Params().tex("roughness", "rough")));
    DielectricBxDF dref(1.5f, TrowbridgeReitz(0.5f, 0.5f));
    EXPECT_NEAR(tex->f(kOblique, wi, TransportMode::Radiance).g, dref.f(kOblique, wi, TransportMode::Radiance).g, 1e-5f);
}

TEST_F(Materials, DielectricEta) {
    auto normalR = [&](const BxDF& b) { return b.sample(kUp, 0, {0.5f, 0.5f}, TransportMode::Radiance)->pdf; };  // P(reflect) = F
    const BxDF* def = bxdf(*make("dielectric", Params()));
    EXPECT_EQ(def->flags(), kReflection | kTransmission | kSpecular);
    EXPECT_NEAR(normalR(*def), 0.04f, 1e-5f);
    const BxDF* f = bxdf(*make("dielectric", Params().f("eta", 1.33)));
    EXPECT_NEAR(normalR(*f), fresnelDielectric(1, 1.33f), 1e-6f);
    // A spectrum eta: one value (green) is used, with a warning.
    int before = warningCount();
    const BxDF* bk7 = bxdf(*make("dielectric", Params().namedSpectrum("eta", "glass-BK7")));
    EXPECT_NEAR(normalR(*bk7), fresnelDielectric(1, 1.5168f), 1e-5f);
    EXPECT_LE(warningCount(), before + 1);
    // eta 1 passes through.
    EXPECT_EQ(bxdf(*make("dielectric", Params().f("eta", 1.0)))->flags(), kTransmission | kSpecular);
    EXPECT_THROW(make("dielectric", Params().f("eta", -1.0)), InputError);
}

TEST_F(Materials, ThinDielectricAndDiffuseTransmission) {
    const BxDF* thin = bxdf(*make("thindielectric", Params()));
    EXPECT_EQ(thin->flags(), kReflection | kTransmission | kSpecular);
    EXPECT_NEAR(thin->sample(kUp, 0, {0, 0}, TransportMode::Radiance)->pdf, 0.08f / 1.04f, 1e-5f);
    const BxDF* dt = bxdf(*make("diffusetransmission", Params()));
    EXPECT_NEAR(dt->f(kUp, kOblique, TransportMode::Radiance).g, 0.25f / kPi, 1e-6f);
    EXPECT_NEAR(dt->f(kUp, -kOblique, TransportMode::Radiance).g, 0.25f / kPi, 1e-6f);
    const BxDF* scaled = bxdf(*make("diffusetransmission", Params().rgb("transmittance", 0.5, 0.5, 0.5).f("scale", 3)));
    EXPECT_NEAR(scaled->f(kUp, -kOblique, TransportMode::Radiance).g, 1 / kPi, 1e-6f);  // 1.5 clamped to 1
    EXPECT_NEAR(scaled->f(kUp, kOblique, TransportMode::Radiance).g, 0.75f / kPi, 1e-6f);
}

TEST_F(Materials, CoatedMaterials) {
    const BxDF* cd = bxdf(*make("coateddiffuse", Params()));
    EXPECT_EQ(cd->flags(), kReflection | kSpecular | kDiffuse);
    float a = albedo(*cd);
    EXPECT_GT(a, 0.2f);
    EXPECT_LT(a, 0.5f);
    const BxDF* rough = bxdf(*make("coateddiffuse", Params().f("roughness", 0.1).rgb("albedo", 0.5, 0.5, 0.5).f("g", 0.3)
                                                         .f("thickness", 0.1).i("maxdepth", 5).i("nsamples", 2)));
    EXPECT_EQ(rough->flags(), kReflection | kDiffuse);
    EXPECT_THROW(make("coateddiffuse", Params().i("nsamples", 0)), InputError);

    const BxDF* cc = bxdf(*make("coatedconductor", Params()));
    EXPECT_EQ(cc->flags(), kReflection | kSpecular);
    const BxDF* ccr = bxdf(*make("coatedconductor", Params().f("interface.roughness", 0.05).f("conductor.roughness", 0.1)
                                                        .rgb("reflectance", 0.8, 0.8, 0.8)));
    EXPECT_EQ(ccr->flags(), kReflection | kGlossy);
    float ac = albedo(*ccr);
    // Coating and rough base (single-scattering GGX loses ~13% at alpha 0.32) reflect less
    // than the bare 0.8.
    EXPECT_GT(ac, 0.3f);
    EXPECT_LT(ac, 0.8f);
    EXPECT_THROW(make("coatedconductor", Params().rgb("reflectance", 0.5, 0.5, 0.5).namedSpectrum("conductor.eta", "metal-Au-eta")),
                 InputError);
    int before = warningCount();
    make("coatedconductor", Params().f("roughness", 0.1));  // the coating's is "interface.roughness"
    EXPECT_EQ(warningCount(), before + 1);
}

TEST_F(Materials, MixChoosesByAmount) {
    named_["red"] = make("diffuse", Params().rgb("reflectance", 1, 0, 0));
    named_["blue"] = make("diffuse", Params().rgb("reflectance", 0, 0, 1));
    auto m = make("mix", Params().s("materials", std::vector<std::string>{"red", "blue"}).f("amount", 0.3));
    Rng rng(5);
    int second = 0;
    const int n = 20000;
    for (int i = 0; i < n; ++i) {
        ctx_.p = Vec3(rng.uniform(), rng.uniform(), rng.uniform());
        const Material* chosen = m->resolve(ctx_);
        EXPECT_EQ(chosen, m->resolve(ctx_));  // deterministic per (p, wo)
        if (chosen == named_["blue"].get()) ++second;
    }
    EXPECT_NEAR(double(second) / n, 0.3, 4 * std::sqrt(0.21 / n));  // materials[1] with probability amount
    auto first = make("mix", Params().s("materials", std::vector<std::string>{"red", "blue"}).f("amount", 0.0));
    EXPECT_EQ(first->resolve(ctx_), named_["red"].get());
    auto last = make("mix", Params().s("materials", std::vector<std::string>{"red", "blue"}).f("amount", 1.0));
    EXPECT_EQ(last->resolve(ctx_), named_["blue"].get());
    EXPECT_NEAR(bxdf(*last)->f(kUp, kOblique, TransportMode::Radiance).b, 1 / kPi, 1e-6f);
    EXPECT_THROW(make("mix", Params().s("materials", std::vector<std::string>{"red", "green"})), InputError);
    EXPECT_THROW(make("mix", Params().s("materials", "red")), InputError);
    named_["none"] = make("interface", Params());
    EXPECT_THROW(make("mix", Params().s("materials", std::vector<std::string>{"red", "none"})), InputError);
}

TEST_F(Materials, InterfaceAndUnknown) {
    auto i = make("interface", Params());
    EXPECT_TRUE(i->isInterface());
    EXPECT_EQ(bxdf(*i), nullptr);
    EXPECT_TRUE(make("none", Params())->isInterface());
    int before = warningCount();
    auto u = make("frobnicate", Params());
    EXPECT_EQ(warningCount(), before + 1);  // one warning naming the type
    EXPECT_NEAR(bxdf(*u)->f(kUp, kOblique, TransportMode::Radiance).g, 0.5f / kPi, 1e-6f);
    EXPECT_NE(warningMessages().back().find("\"frobnicate\" is not supported"), std::string::npos) << warningMessages().back();
    // subsurface is supported (tests/materials/subsurface_test.cpp): no warning.
    before = warningCount();
    make("subsurface", Params().f("eta", 1.33));
    EXPECT_EQ(warningCount(), before);
    before = warningCount();
    // Unknown parameters of known materials warn.
    make("diffuse", Params().f("roughness", 0.2));
    EXPECT_EQ(warningCount(), before + 1);
}

}  // namespace
