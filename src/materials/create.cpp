// Materials and textures from the scene's parameter lists, with pbrt-v4's parameter names
// and defaults (PBRT-CONVENTIONS §5, §6; pbrt-v4 materials.cpp / textures.cpp Create()).
#include "materials/create.h"

#include <atomic>
#include <type_traits>

#include "materials/hair_bxdf.h"
#include "materials/hair_material.h"
#include "materials/image_texture.h"
#include "materials/materials.h"
#include "materials/measured_material.h"
#include "materials/named_scattering.h"
#include "materials/procedural_textures.h"
#include "materials/shading_detail.h"
#include "materials/spectral_textures.h"
#include "materials/subsurface_material.h"
#include "materials/beam_diffusion.h"
#include "materials/textures.h"
#include "scene/spectra.h"
#include "spectral/cie.h"
#include "spectral/named_spectra.h"
#include "util/path.h"

namespace ps {

namespace {

const SourceLoc& locOf(const ParamSet& ps, const std::string& name) {
    const Param* p = ps.find(name);
    return p ? p->loc : ps.loc;
}

// A float parameter given as a constant or as `"texture name" "tex"`.
FloatTex floatParam(const ParamSet& ps, const std::string& name, float def, const TextureRegistry& reg) {
    std::string tex = ps.getTexture(name);
    if (!tex.empty()) {
        auto it = reg.floats.find(tex);
        if (it == reg.floats.end())
            throw InputError(locOf(ps, name), "float texture \"" + tex + "\" (for \"" + name + "\") is not defined");
        return it->second;
    }
    return std::make_shared<ConstantTexture<float>>(ps.getFloat(name, def));
}

// A spectrum parameter as a texture or as rgb / spectrum / blackbody; def when absent
// (nullptr when def is nullopt). Constants keep their spectrum for spectral mode; textures
// are lifted by `kind` there (materials/spectral_textures.h).
SpectrumTex spectrumParam(const ParamSet& ps, const std::string& name, std::optional<Spectrum> def, SpectrumKind kind,
                          const TextureRegistry& reg) {
    std::string tex = ps.getTexture(name);
    if (!tex.empty()) {
        auto it = reg.spectra.find(tex);
        if (it == reg.spectra.end())
            throw InputError(locOf(ps, name), "spectrum texture \"" + tex + "\" (for \"" + name + "\") is not defined");
        return std::make_shared<LiftedSpectrumTexture>(it->second, kind);
    }
    if (auto s = ps.getSpectrum(name, kind))
        return std::make_shared<SpectralConstantTexture>(*s, *ps.getSpectrumSource(name, kind));
    if (def) return std::make_shared<SpectralConstantTexture>(*def, SpectrumSource::constant(def->g));
    return nullptr;
}

// A constant from one of pbrt-v4's named spectra (defaults such as copper's eta and k).
SpectrumTex namedConstant(const std::string& name, SpectrumKind kind) {
    return std::make_shared<SpectralConstantTexture>(*namedSpectrumToRGB(name, kind), *namedSpectrum(name));
}

SpectrumTex constantSpectrum(const Spectrum& s) { return std::make_shared<ConstantTexture<Spectrum>>(s); }

// uroughness / vroughness, each defaulting to roughness (0); remaproughness (true).
Roughness roughness(const ParamSet& ps, const TextureRegistry& reg, const std::string& prefix = "") {
    Roughness r;
    r.u = ps.has(prefix + "uroughness") ? floatParam(ps, prefix + "uroughness", 0, reg) : floatParam(ps, prefix + "roughness", 0, reg);
    r.v = ps.has(prefix + "vroughness") ? floatParam(ps, prefix + "vroughness", 0, reg) : floatParam(ps, prefix + "roughness", 0, reg);
    r.remap = ps.getBool("remaproughness", true);
    return r;
}

// A dielectric's index: `float` (the first value), or a spectrum. pbrt-v4 then follows one
// wavelength (dispersion): so does spectral mode; in RGB we keep the green channel's value
// and say so once (in spectral mode there is nothing to say).
IndexOfRefraction etaParam(const ParamSet& ps, const std::string& name, bool spectralMode) {
    const Param* p = ps.find(name);
    IndexOfRefraction eta;
    if (p && p->type == ParamType::Float) {
        std::vector<float> v = ps.getFloats(name);
        if (v.empty()) throw InputError(p->loc, "\"float " + name + "\" needs a value");
        eta.value = v[0];
    } else if (auto s = ps.getSpectrum(name, SpectrumKind::Unbounded)) {
        static std::atomic<bool> warned{false};
        if (ps.spectrallyVarying(name)) {
            eta.dispersive = ps.getSpectrumSource(name, SpectrumKind::Unbounded);
            if (!spectralMode && !warned.exchange(true))
                warning(p->loc, "spectrally varying \"" + name + "\": dispersion is modelled in spectral mode only "
                                "(--color spectral); RGB mode uses the green channel's value " + std::to_string(s->g) +
                                " (warned once)");
        }
        eta.value = s->g;
    }
    // A textured index is not a pbrt-v4 feature: left unused, reportUnused names it.
    if (eta.value == 0) eta.value = 1;  // as pbrt-v4
    if (!(eta.value > 0) || !std::isfinite(eta.value)) throw InputError(p ? p->loc : ps.loc, "\"" + name + "\" must be positive");
    return eta;
}

LayerTextures layerParams(const ParamSet& ps, const TextureRegistry& reg) {
    LayerTextures l;
    l.thickness = floatParam(ps, "thickness", 0.01f, reg);
    l.g = floatParam(ps, "g", 0, reg);
    l.albedo = spectrumParam(ps, "albedo", Spectrum(0.0f), SpectrumKind::Albedo, reg);
    l.maxDepth = ps.getInt("maxdepth", 10);
    l.nSamples = ps.getInt("nsamples", 1);
    if (l.maxDepth < 0) throw InputError(locOf(ps, "maxdepth"), "\"maxdepth\" must not be negative");
    if (l.nSamples < 1) throw InputError(locOf(ps, "nsamples"), "\"nsamples\" must be at least 1");
    return l;
}

// Conductor eta / k (default copper) or reflectance; giving both forms is an error.
void conductorParams(const ParamSet& ps, const TextureRegistry& reg, const std::string& prefix, const std::string& what,
                     SpectrumTex& eta, SpectrumTex& k, SpectrumTex& reflectance) {
    const SpectrumKind U = SpectrumKind::Unbounded;
    reflectance = spectrumParam(ps, "reflectance", std::nullopt, SpectrumKind::Albedo, reg);
    eta = spectrumParam(ps, prefix + "eta", std::nullopt, U, reg);
    k = spectrumParam(ps, prefix + "k", std::nullopt, U, reg);
    if (reflectance && (eta || k))
        throw InputError(locOf(ps, "reflectance"),
                         what + ": give either \"reflectance\" or \"" + prefix + "eta\"/\"" + prefix + "k\", not both");
    if (reflectance) return;
    if (!eta) eta = namedConstant("metal-Cu-eta", U);
    if (!k) k = namedConstant("metal-Cu-k", U);
}

// pbrt-v4's hair parameters: sigma_a wins over reflectance (alias "color"), which wins over
// the melanin concentrations, each ignored with a warning; none of them means eumelanin 1.3.
HairTextures hairParams(const ParamSet& ps, const TextureRegistry& reg) {
    HairTextures t;
    t.sigmaA = spectrumParam(ps, "sigma_a", std::nullopt, SpectrumKind::Unbounded, reg);
    const char* reflName = ps.has("reflectance") ? "reflectance" : "color";
    t.reflectance = spectrumParam(ps, reflName, std::nullopt, SpectrumKind::Albedo, reg);
    if (ps.has("eumelanin")) t.eumelanin = floatParam(ps, "eumelanin", 0, reg);
    if (ps.has("pheomelanin")) t.pheomelanin = floatParam(ps, "pheomelanin", 0, reg);
    const std::string why = t.sigmaA ? "sigma_a" : t.reflectance ? reflName : "";
    auto ignore = [&](auto& tex, const std::string& name) {
        if (!tex) return;
        warning(locOf(ps, name), "hair: \"" + name + "\" is ignored since \"" + why + "\" is given");
        tex = nullptr;
    };
    if (t.sigmaA) ignore(t.reflectance, reflName);
    if (!why.empty()) {
        ignore(t.eumelanin, "eumelanin");
        ignore(t.pheomelanin, "pheomelanin");
    }
    if (!t.sigmaA && !t.reflectance && !t.eumelanin && !t.pheomelanin)
        t.sigmaA = constantSpectrum(HairBxDF::sigmaAFromConcentration(1.3f, 0));
    t.eta = floatParam(ps, "eta", 1.55f, reg);
    t.betaM = floatParam(ps, "beta_m", 0.3f, reg);
    t.betaN = floatParam(ps, "beta_n", 0.3f, reg);
    t.alpha = floatParam(ps, "alpha", 2, reg);
    return t;
}

// ---- subsurface (pbrt-v4's SubsurfaceMaterial::Create) ----

// A constant coefficient of the interior medium; a texture cannot vary a homogeneous medium
// with the entry point, so it is refused where it is given rather than replaced silently.
std::optional<MediumSpectrum> constantCoefficient(const ParamSet& ps, const std::string& name, SpectrumKind kind,
                                                  float scale) {
    if (!ps.getTexture(name).empty())
        throw InputError(locOf(ps, name), "subsurface: \"" + name + "\" is a texture; the random walk's interior is one "
                                          "homogeneous medium, so it takes a constant (rgb, spectrum or blackbody) value");
    auto rgb = ps.getSpectrum(name, kind);
    if (!rgb) return std::nullopt;
    const Spectrum v = *rgb * scale;
    if (!(std::min({v.r, v.g, v.b}) >= 0) || !std::isfinite(v.maxComponent()))
        throw InputError(locOf(ps, name), "subsurface: \"" + name + "\" must be finite and not negative");
    return MediumSpectrum(v, *ps.getSpectrumSource(name, kind), scale);
}

// "reflectance" with "mfp" (pbrt-v4's SubsurfaceFromDiffuse): per channel, and in spectral
// mode per wavelength on the 1 nm grid, the albedo rho whose beam-diffusion reflectance is
// the given one; sigma_s = rho / mfp, sigma_a = (1 - rho) / mfp, with mfp times "scale".
void coefficientsFromReflectance(const ParamSet& ps, const MediumSpectrum& refl, const MediumSpectrum& mfp,
                                 const EffectiveAlbedoTable& table, SubsurfaceInterior& in) {
    auto split = [&](float r, float m, float& sa, float& ss) {
        const float rho = albedoForReflectance(table, r);
        ss = rho / m;
        sa = (1 - rho) / m;
    };
    const Spectrum R = refl(nullptr), M = mfp(nullptr);
    if (!(std::min({M.r, M.g, M.b}) > 0)) throw InputError(locOf(ps, "mfp"), "subsurface: \"mfp\" (times \"scale\") must be positive");
    Spectrum sa, ss;
    for (int c = 0; c < 3; ++c) split(R[c], M[c], sa[c], ss[c]);
    auto denseA = std::make_shared<DenseSpectrum>(), denseS = std::make_shared<DenseSpectrum>();
    for (int i = 0; i < kCieSamples; ++i) {
        SampledWavelengths w;
        w.lambda.fill(float(kCieLambdaMin + i));
        const float r = refl(&w)[0], m = mfp(&w)[0];
        if (!(m > 0)) throw InputError(locOf(ps, "mfp"), "subsurface: \"mfp\" (times \"scale\") must be positive at every wavelength");
        split(r, m, denseA->value[i], denseS->value[i]);
    }
    in.sigmaA = MediumSpectrum(Spectrum(sa.r, sa.g, sa.b), SpectrumSource::dense(denseA), 1);
    in.sigmaS = MediumSpectrum(Spectrum(ss.r, ss.g, ss.b), SpectrumSource::dense(denseS), 1);
}

// Four exclusive forms, as pbrt-v4: "name" (measured, g forced to 0), sigma_a with sigma_s,
// reflectance (with mfp, default 1), or none (pbrt-v4's default, Jensen et al.'s whole milk).
// "scale" multiplies the coefficients, or mfp.
std::shared_ptr<Material> subsurfaceMaterial(const ParamSet& ps, const TextureRegistry& reg) {
    const SpectrumKind U = SpectrumKind::Unbounded;
    SubsurfaceInterior in;
    in.g = ps.getFloat("g", 0);
    if (!(in.g > -1 && in.g < 1)) throw InputError(locOf(ps, "g"), "subsurface: \"g\" must be between -1 and 1");
    const float scale = ps.getFloat("scale", 1);
    if (!(scale >= 0) || !std::isfinite(scale)) throw InputError(locOf(ps, "scale"), "subsurface: \"scale\" must be finite and at least 0");
    const float eta = ps.getFloat("eta", 1.33f);
    if (!(eta > 0) || !std::isfinite(eta)) throw InputError(locOf(ps, "eta"), "subsurface: \"eta\" must be positive");
    const std::string name = ps.getString("name", "");
    if (!name.empty()) {
        auto measured = namedScattering(name);
        if (!measured)
            throw InputError(locOf(ps, "name"), "subsurface: no measured medium is named " + quoteForMessage(name) +
                                                    " (known: " + namedScatteringList() + ")");
        if (in.g != 0) warning(locOf(ps, "g"), "subsurface: \"g\" is ignored with \"name\" (its coefficients are reduced ones, for g = 0)");
        in.g = 0;
        in.sigmaA = srgbCoefficient(measured->sigmaA, scale);
        in.sigmaS = srgbCoefficient(measured->sigmaS, scale);
    } else if (ps.has("sigma_a") || ps.has("sigma_s")) {
        auto a = constantCoefficient(ps, "sigma_a", U, scale), s = constantCoefficient(ps, "sigma_s", U, scale);
        if (!a || !s)
            throw InputError(locOf(ps, a ? "sigma_a" : "sigma_s"), std::string("subsurface: \"") + (a ? "sigma_a" : "sigma_s") +
                                                                       "\" is given without \"" + (a ? "sigma_s" : "sigma_a") + "\"");
        in.sigmaA = *a;
        in.sigmaS = *s;
    } else if (ps.has("reflectance")) {
        auto refl = constantCoefficient(ps, "reflectance", SpectrumKind::Albedo, 1);
        auto mfp = constantCoefficient(ps, "mfp", U, scale);
        if (!refl) throw InputError(locOf(ps, "reflectance"), "subsurface: \"reflectance\" must be an rgb, spectrum or blackbody value");
        coefficientsFromReflectance(ps, *refl, mfp ? *mfp : MediumSpectrum(Spectrum(scale), SpectrumSource::constant(1), scale),
                                    effectiveAlbedoTable(in.g, eta), in);
    } else {
        in.sigmaA = srgbCoefficient({0.0011f, 0.0024f, 0.014f}, scale);
        in.sigmaS = srgbCoefficient({2.55f, 3.21f, 3.77f}, scale);
    }
    return std::make_shared<SubsurfaceMaterial>(eta, roughness(ps, reg), std::move(in));
}

std::shared_ptr<Material> defaultDiffuse() {
    return std::make_shared<DiffuseMaterial>(std::make_shared<SpectralConstantTexture>(Spectrum(0.5f), SpectrumSource::constant(0.5f)));
}

ImageLookup imageLookup(const TextureEntity& e, const std::string& base, bool isFloat) {
    const ParamSet& ps = e.params;
    std::string file = ps.getString("filename", "");
    if (file.empty()) throw InputError(e.loc, "imagemap: \"string filename\" is required");
    std::string path = resolvePath(base, file);
    // pbrt-v4 honours `encoding` for PNG only (8-bit formats are always sRGB, floats linear).
    std::string enc = ps.getString("encoding", lowerExtension(file) == ".png" ? "sRGB" : "linear");
    if (enc != "linear" && enc != "sRGB") warning(locOf(ps, "encoding"), "imagemap: encoding \"" + enc + "\" is not supported; using sRGB");
    ColorEncoding ce = enc == "linear" ? ColorEncoding::Linear : ColorEncoding::SRGB;
    std::string wrap = ps.getString("wrap", "repeat");
    WrapMode wm = WrapMode::Repeat;
    if (wrap == "clamp") wm = WrapMode::Clamp;
    else if (wrap == "black") wm = WrapMode::Black;
    else if (wrap != "repeat") warning(locOf(ps, "wrap"), "imagemap: wrap \"" + wrap + "\" is not supported; using \"repeat\"");
    std::string filter = ps.getString("filter", "bilinear");
    if (filter != "bilinear" && filter != "point" && filter != "trilinear" && filter != "ewa" && filter != "EWA")
        warning(locOf(ps, "filter"), "imagemap: unknown filter \"" + filter + "\"; using bilinear");
    ps.getFloat("maxanisotropy", 8);
    auto img = readNamedBy(e.loc, [&] { return loadTextureImage(path, ce); });
    ImageChannels ch = !isFloat ? ImageChannels::RGB : hasNonOpaqueAlpha(*img) ? ImageChannels::Alpha : ImageChannels::Average;
    return ImageLookup(img, textureMapping2D(ps, e.worldFromTexture, e.loc), wm, ps.getFloat("scale", 1), ps.getBool("invert", false), ch);
}

// A unit direction parameter given in the texture's space, taken to world space by its CTM.
Vec3 directionParam(const TextureEntity& e, const std::string& name, Vec3 def) {
    Vec3 d = e.worldFromTexture.vector(e.params.getVector3(name, def));
    float len = length(d);
    if (!(len > 0) || !std::isfinite(len))
        throw InputError(locOf(e.params, name), "\"" + name + "\" must be a non-zero direction (after the texture's transform)");
    return d / len;
}

// The noise textures' "octaves" (8 by default); 1.99^i p overflows float beyond ~100 octaves.
int octavesParam(const ParamSet& ps) {
    int octaves = ps.getInt("octaves", 8);
    if (octaves < 0 || octaves > 64) throw InputError(locOf(ps, "octaves"), "\"octaves\" must be between 0 and 64");
    return octaves;
}

// Float and spectrum textures share their classes and parameter names; `get` reads one
// parameter of the texture's own kind as a texture or a constant, `constant` as a constant only.
template <typename T>
struct TexParams;
template <>
struct TexParams<float> {
    static FloatTex get(const ParamSet& ps, const std::string& n, float def, const TextureRegistry& reg) {
        return floatParam(ps, n, def, reg);
    }
    static float constant(const ParamSet& ps, const std::string& n, float def) { return ps.getFloat(n, def); }
};
template <>
struct TexParams<Spectrum> {
    // Spectrum textures feed albedos and unbounded quantities alike: values are kept as
    // given, and materials clamp albedos themselves.
    static SpectrumTex get(const ParamSet& ps, const std::string& n, float def, const TextureRegistry& reg) {
        return spectrumParam(ps, n, Spectrum(def), SpectrumKind::Unbounded, reg);
    }
    static Spectrum constant(const ParamSet& ps, const std::string& n, float def) {
        return ps.getSpectrum(n, SpectrumKind::Unbounded).value_or(Spectrum(def));
    }
};

template <typename T>
std::shared_ptr<typename TextureOf<T>::type> createTexture(const TextureEntity& e, const TextureRegistry& reg,
                                                           const std::string& base) {
    using P = TexParams<T>;
    using Ptr = std::shared_ptr<typename TextureOf<T>::type>;
    const ParamSet& ps = e.params;
    Ptr t;
    if (e.type == "constant") {
        t = P::get(ps, "value", 1, reg);
    } else if (e.type == "scale") {
        t = std::make_shared<ScaleTexture<T>>(P::get(ps, "tex", 1, reg), floatParam(ps, "scale", 1, reg));
    } else if (e.type == "mix") {
        t = std::make_shared<MixTexture<T>>(P::get(ps, "tex1", 0, reg), P::get(ps, "tex2", 1, reg), floatParam(ps, "amount", 0.5f, reg));
    } else if (e.type == "checkerboard") {
        int dim = ps.getInt("dimension", 2);
        if (dim != 2 && dim != 3) throw InputError(locOf(ps, "dimension"), "checkerboard: \"dimension\" must be 2 or 3");
        auto tex1 = P::get(ps, "tex1", 1, reg), tex2 = P::get(ps, "tex2", 0, reg);
        if (dim == 2) t = std::make_shared<CheckerboardTexture<T>>(textureMapping2D(ps, e.worldFromTexture, e.loc), tex1, tex2);
        else t = std::make_shared<CheckerboardTexture<T>>(textureMapping3D(e.worldFromTexture, e.loc), tex1, tex2);
    } else if (e.type == "directionmix") {
        t = std::make_shared<DirectionMixTexture<T>>(P::get(ps, "tex1", 0, reg), P::get(ps, "tex2", 1, reg),
                                                     directionParam(e, "dir", Vec3(0, 1, 0)));
    } else if (e.type == "dots") {
        // pbrt-v4 hands "inside" to the region outside the dots and "outside" to the dots
        // (its constructor takes them in the other order); kept, so images match.
        t = std::make_shared<DotsTexture<T>>(textureMapping2D(ps, e.worldFromTexture, e.loc), P::get(ps, "outside", 0, reg),
                                             P::get(ps, "inside", 1, reg));
    } else if (e.type == "bilerp") {
        auto corner = [&](const char* n, float def) { return P::constant(ps, n, def); };  // constants only, as pbrt-v4
        t = std::make_shared<BilerpTexture<T>>(textureMapping2D(ps, e.worldFromTexture, e.loc), corner("v00", 0), corner("v01", 1),
                                               corner("v10", 0), corner("v11", 1));
    } else if (std::is_same_v<T, float> && (e.type == "fbm" || e.type == "wrinkled" || e.type == "windy")) {
        TextureMapping3D map = textureMapping3D(e.worldFromTexture, e.loc);
        if constexpr (std::is_same_v<T, float>) {
            if (e.type == "windy") t = std::make_shared<WindyTexture>(map);
            else if (e.type == "fbm") t = std::make_shared<FBmTexture>(map, octavesParam(ps), ps.getFloat("roughness", 0.5f));
            else t = std::make_shared<WrinkledTexture>(map, octavesParam(ps), ps.getFloat("roughness", 0.5f));
        }
    } else if (!std::is_same_v<T, float> && e.type == "marble") {
        if constexpr (!std::is_same_v<T, float>)
            t = std::make_shared<MarbleTexture>(textureMapping3D(e.worldFromTexture, e.loc), octavesParam(ps),
                                                ps.getFloat("roughness", 0.5f), ps.getFloat("scale", 1), ps.getFloat("variation", 0.2f));
    } else if (e.type == "imagemap") {
        if constexpr (std::is_same_v<T, float>)
            t = std::make_shared<FloatImageTexture>(imageLookup(e, base, true));
        else
            t = std::make_shared<SpectrumImageTexture>(imageLookup(e, base, false));
    } else {
        warning(e.loc, std::string(std::is_same_v<T, float> ? "float" : "spectrum") + " texture class \"" + e.type +
                           "\" is not supported; using constant 1");
        return P::get(ParamSet{}, "value", 1, reg);
    }
    ps.reportUnused("Texture \"" + e.name + "\"");
    return t;
}

// "string normalmap" (a file) or "displacement" (a float texture): the bump or normal map
// of a scattering material, or null. The normal map wins when both are given (as pbrt-v4).
std::shared_ptr<const ShadingDetail> shadingDetailParam(const std::string& type, const ParamSet& ps,
                                                        const TextureRegistry& reg, const std::string& base) {
    if (!ps.has("normalmap") && !ps.has("displacement")) return nullptr;
    if (type == "mix" || type == "interface" || type == "" || type == "none" || type == "hair") {
        // mix chooses a member first, whose own map then applies; interface does not scatter.
        const char* name = ps.has("normalmap") ? "normalmap" : "displacement";
        ps.getString("normalmap", "");
        ps.getTexture("displacement");
        ps.getFloat("displacement", 0);
        warning(locOf(ps, name), "\"" + std::string(name) + "\" has no effect on a \"" + type + "\" material; ignored");
        return nullptr;
    }
    std::string file = ps.getString("normalmap", "");
    if (!file.empty()) {
        ps.getTexture("displacement");
        ps.getFloat("displacement", 0);
        std::string path = resolvePath(base, file);
        // Read linearly: only PNG honours an encoding, other 8-bit formats are sRGB-decoded.
        auto img = readNamedBy(locOf(ps, "normalmap"), [&] { return loadTextureImage(path, ColorEncoding::Linear); });
        return ShadingDetail::normalMap(std::move(img));
    }
    if (!ps.has("displacement")) return nullptr;  // an empty normalmap string: none, as pbrt-v4
    return ShadingDetail::bumpMap(floatParam(ps, "displacement", 0, reg));
}

}  // namespace

std::shared_ptr<FloatTexture> floatTextureParam(const ParamSet& ps, const std::string& name, float def,
                                                const TextureRegistry& reg) {
    return floatParam(ps, name, def, reg);
}

std::shared_ptr<FloatTexture> createFloatTexture(const TextureEntity& e, const TextureRegistry& reg, const std::string& base) {
    return createTexture<float>(e, reg, base);
}

std::shared_ptr<SpectrumTexture> createSpectrumTexture(const TextureEntity& e, const TextureRegistry& reg, const std::string& base) {
    return createTexture<Spectrum>(e, reg, base);
}

std::shared_ptr<Material> createMaterial(const std::string& type, const ParamSet& ps, const TextureRegistry& reg,
                                         const std::map<std::string, std::shared_ptr<Material>>& named, const std::string& base,
                                         bool spectralMode) {
    const SpectrumKind A = SpectrumKind::Albedo;
    std::shared_ptr<Material> m;
    if (type == "diffuse") {
        m = std::make_shared<DiffuseMaterial>(spectrumParam(ps, "reflectance", Spectrum(0.5f), A, reg));
    } else if (type == "conductor") {
        SpectrumTex eta, k, refl;
        conductorParams(ps, reg, "", "conductor", eta, k, refl);
        m = std::make_shared<ConductorMaterial>(eta, k, refl, roughness(ps, reg));
    } else if (type == "dielectric") {
        IndexOfRefraction eta = etaParam(ps, "eta", spectralMode);
        m = std::make_shared<DielectricMaterial>(eta, roughness(ps, reg));
    } else if (type == "thindielectric") {
        m = std::make_shared<ThinDielectricMaterial>(etaParam(ps, "eta", spectralMode));
    } else if (type == "diffusetransmission") {
        m = std::make_shared<DiffuseTransmissionMaterial>(spectrumParam(ps, "reflectance", Spectrum(0.25f), A, reg),
                                                          spectrumParam(ps, "transmittance", Spectrum(0.25f), A, reg),
                                                          ps.getFloat("scale", 1));
    } else if (type == "coateddiffuse") {
        CoatedDiffuseParams p;
        p.reflectance = spectrumParam(ps, "reflectance", Spectrum(0.5f), A, reg);
        p.roughness = roughness(ps, reg);
        p.eta = etaParam(ps, "eta", spectralMode);
        p.layer = layerParams(ps, reg);
        m = std::make_shared<CoatedDiffuseMaterial>(p);
    } else if (type == "coatedconductor") {
        CoatedConductorParams p;
        p.interfaceRoughness = roughness(ps, reg, "interface.");
        p.interfaceEta = etaParam(ps, "interface.eta", spectralMode);
        conductorParams(ps, reg, "conductor.", "coatedconductor", p.conductorEta, p.conductorK, p.reflectance);
        p.conductorRoughness = roughness(ps, reg, "conductor.");
        p.layer = layerParams(ps, reg);
        m = std::make_shared<CoatedConductorMaterial>(p);
    } else if (type == "mix") {
        std::vector<std::string> names = ps.getStrings("materials");
        if (names.size() != 2) throw InputError(locOf(ps, "materials"), "mix: \"string materials\" must name exactly two materials");
        std::array<std::shared_ptr<Material>, 2> ms;
        for (int i = 0; i < 2; ++i) {
            auto it = named.find(names[i]);
            if (it == named.end()) throw InputError(locOf(ps, "materials"), "mix: material \"" + names[i] + "\" is not defined");
            if (it->second->isInterface()) throw InputError(locOf(ps, "materials"), "mix: \"interface\" cannot be mixed");
            // Its interior medium belongs to the shape, which a mix chooses point by point.
            if (dynamic_cast<const SubsurfaceMaterial*>(it->second.get()))
                throw InputError(locOf(ps, "materials"), "mix: \"subsurface\" cannot be mixed (its medium fills the whole shape)");
            ms[i] = it->second;
        }
        m = std::make_shared<MixMaterial>(ms, floatParam(ps, "amount", 0.5f, reg));
    } else if (type == "measured") {
        std::string file = ps.getString("filename", "");
        if (file.empty()) throw InputError(ps.loc, "measured: \"string filename\" (a .bsdf file) is required");
        std::string path = resolvePath(base, file);
        m = std::make_shared<MeasuredMaterial>(readNamedBy(ps.loc, [&] { return MeasuredBRDF::load(path); }));
    } else if (type == "hair") {
        m = std::make_shared<HairMaterial>(hairParams(ps, reg));
    } else if (type == "subsurface") {
        m = subsurfaceMaterial(ps, reg);
    } else if (type == "interface" || type == "" || type == "none") {
        m = std::make_shared<InterfaceMaterial>();
    } else {
        // Its parameters are all unknown too; the one warning says what happened.
        warning(ps.loc, "material \"" + type + "\" is not supported; using diffuse 0.5");
        return defaultDiffuse();
    }
    if (auto detail = shadingDetailParam(type, ps, reg, base)) m->setShadingDetail(std::move(detail));
    ps.reportUnused("Material \"" + type + "\"");
    return m;
}

}  // namespace ps
