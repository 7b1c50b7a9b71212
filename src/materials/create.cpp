#include "materials/create.h"

#include <filesystem>

#include "materials/materials.h"
#include "materials/textures.h"
#include "scene/spectra.h"
#include "util/path.h"

namespace ps {

namespace {

// A float parameter given as a constant or as `"texture name" "tex"`.
FloatTex floatParam(const ParamSet& ps, const std::string& name, float def, const TextureRegistry& reg) {
    std::string tex = ps.getTexture(name);
    if (!tex.empty()) {
        auto it = reg.floats.find(tex);
        if (it == reg.floats.end()) throw InputError(ps.loc, "float texture \"" + tex + "\" (for \"" + name + "\") is not defined");
        return it->second;
    }
    return std::make_shared<ConstantTexture<float>>(ps.getFloat(name, def));
}

SpectrumTex spectrumParam(const ParamSet& ps, const std::string& name, std::optional<Spectrum> def, SpectrumKind kind,
                          const TextureRegistry& reg) {
    std::string tex = ps.getTexture(name);
    if (!tex.empty()) {
        auto it = reg.spectra.find(tex);
        if (it == reg.spectra.end()) throw InputError(ps.loc, "spectrum texture \"" + tex + "\" (for \"" + name + "\") is not defined");
        return it->second;
    }
    if (auto s = ps.getSpectrum(name, kind)) return std::make_shared<ConstantTexture<Spectrum>>(*s);
    if (def) return std::make_shared<ConstantTexture<Spectrum>>(*def);
    return nullptr;
}

Roughness roughness(const ParamSet& ps, const TextureRegistry& reg, const std::string& prefix = "") {
    Roughness r;
    FloatTex base = floatParam(ps, prefix + "roughness", 0, reg);
    r.u = ps.has(prefix + "uroughness") ? floatParam(ps, prefix + "uroughness", 0, reg) : base;
    r.v = ps.has(prefix + "vroughness") ? floatParam(ps, prefix + "vroughness", 0, reg) : base;
    r.remap = ps.getBool("remaproughness", true);
    return r;
}

// Dielectric eta: a float, or a spectrum (whose dispersion we cannot model).
float etaParam(const ParamSet& ps, const std::string& name) {
    const Param* p = ps.find(name);
    if (p && p->type != ParamType::Float) {
        if (auto s = ps.getSpectrum(name, SpectrumKind::Unbounded)) {
            warning(p->loc, "spectrally varying \"" + name + "\": dispersion is not modelled; using its green value " +
                                std::to_string(s->g));
            return s->g;
        }
    }
    if (p && p->type == ParamType::Texture) {
        ps.getTexture(name);
        warning(p->loc, "textured \"" + name + "\" is not supported; using 1.5");
        return 1.5f;
    }
    float eta = ps.getFloat(name, 1.5f);
    if (!(eta > 0)) throw InputError(p ? p->loc : ps.loc, "\"" + name + "\" must be positive");
    return eta;
}

UVMapping uvMapping(const ParamSet& ps, const SourceLoc& loc) {
    std::string m = ps.getString("mapping", "uv");
    if (m != "uv") warning(loc, "texture mapping \"" + m + "\" is not supported; using \"uv\"");
    ps.getFloats("v1");
    ps.getFloats("v2");
    return UVMapping{ps.getFloat("uscale", 1), ps.getFloat("vscale", 1), ps.getFloat("udelta", 0), ps.getFloat("vdelta", 0)};
}

ImageLookup imageLookup(const TextureEntity& e, const std::string& base) {
    const ParamSet& ps = e.params;
    std::string file = ps.getString("filename", "");
    if (file.empty()) throw InputError(e.loc, "imagemap: \"string filename\" is required");
    std::string path = resolvePath(base, file);
    std::string ext = lowerExtension(file);
    std::string enc = ps.getString("encoding", ext == ".png" ? "sRGB" : "linear");
    ColorEncoding ce = enc == "linear" ? ColorEncoding::Linear : ColorEncoding::SRGB;
    if (enc != "linear" && enc != "sRGB") warning(e.loc, "imagemap: encoding \"" + enc + "\" is not supported; using sRGB");
    std::string wrap = ps.getString("wrap", "repeat");
    WrapMode wm = wrap == "clamp" ? WrapMode::Clamp : wrap == "black" ? WrapMode::Black : WrapMode::Repeat;
    if (wrap != "clamp" && wrap != "black" && wrap != "repeat")
        warning(e.loc, "imagemap: wrap \"" + wrap + "\" is not supported; using \"repeat\"");
    ps.getString("filter", "bilinear");
    ps.getFloat("maxanisotropy", 8);
    return ImageLookup(loadTextureImage(path, ce), uvMapping(ps, e.loc), wm, ps.getFloat("scale", 1), ps.getBool("invert", false));
}

template <typename T>
std::shared_ptr<typename TextureOf<T>::type> createTexture(const TextureEntity& e, const TextureRegistry& reg,
                                                           const std::string& base);

template <>
std::shared_ptr<FloatTexture> createTexture<float>(const TextureEntity& e, const TextureRegistry& reg, const std::string& base) {
    const ParamSet& ps = e.params;
    std::shared_ptr<FloatTexture> t;
    if (e.type == "constant") t = floatParam(ps, "value", 1, reg);
    else if (e.type == "scale") t = std::make_shared<ScaleTexture<float>>(floatParam(ps, "tex", 1, reg), floatParam(ps, "scale", 1, reg));
    else if (e.type == "mix")
        t = std::make_shared<MixTexture<float>>(floatParam(ps, "tex1", 0, reg), floatParam(ps, "tex2", 1, reg), floatParam(ps, "amount", 0.5f, reg));
    else if (e.type == "checkerboard") {
        if (ps.getInt("dimension", 2) != 2) warning(e.loc, "checkerboard: only dimension 2 is supported");
        t = std::make_shared<CheckerboardTexture<float>>(uvMapping(ps, e.loc), floatParam(ps, "tex1", 1, reg), floatParam(ps, "tex2", 0, reg));
    } else if (e.type == "imagemap") t = std::make_shared<FloatImageTexture>(imageLookup(e, base));
    else {
        warning(e.loc, "float texture class \"" + e.type + "\" is not supported; using constant 1");
        return std::make_shared<ConstantTexture<float>>(1.0f);
    }
    ps.reportUnused("Texture \"" + e.name + "\"");
    return t;
}

template <>
std::shared_ptr<SpectrumTexture> createTexture<Spectrum>(const TextureEntity& e, const TextureRegistry& reg, const std::string& base) {
    const ParamSet& ps = e.params;
    // Spectrum textures feed reflectances as well as other quantities; Unbounded keeps
    // values as given (materials clamp albedos themselves).
    const SpectrumKind k = SpectrumKind::Unbounded;
    std::shared_ptr<SpectrumTexture> t;
    if (e.type == "constant") t = spectrumParam(ps, "value", Spectrum(1.0f), k, reg);
    else if (e.type == "scale") t = std::make_shared<ScaleTexture<Spectrum>>(spectrumParam(ps, "tex", Spectrum(1.0f), k, reg), floatParam(ps, "scale", 1, reg));
    else if (e.type == "mix")
        t = std::make_shared<MixTexture<Spectrum>>(spectrumParam(ps, "tex1", Spectrum(0.0f), k, reg), spectrumParam(ps, "tex2", Spectrum(1.0f), k, reg),
                                                   floatParam(ps, "amount", 0.5f, reg));
    else if (e.type == "checkerboard") {
        if (ps.getInt("dimension", 2) != 2) warning(e.loc, "checkerboard: only dimension 2 is supported");
        t = std::make_shared<CheckerboardTexture<Spectrum>>(uvMapping(ps, e.loc), spectrumParam(ps, "tex1", Spectrum(1.0f), k, reg),
                                                            spectrumParam(ps, "tex2", Spectrum(0.0f), k, reg));
    } else if (e.type == "imagemap") t = std::make_shared<SpectrumImageTexture>(imageLookup(e, base));
    else {
        warning(e.loc, "spectrum texture class \"" + e.type + "\" is not supported; using constant 1");
        return std::make_shared<ConstantTexture<Spectrum>>(Spectrum(1.0f));
    }
    ps.reportUnused("Texture \"" + e.name + "\"");
    return t;
}

}  // namespace

std::shared_ptr<FloatTexture> createFloatTexture(const TextureEntity& e, const TextureRegistry& reg, const std::string& base) {
    return createTexture<float>(e, reg, base);
}

std::shared_ptr<SpectrumTexture> createSpectrumTexture(const TextureEntity& e, const TextureRegistry& reg, const std::string& base) {
    return createTexture<Spectrum>(e, reg, base);
}

std::shared_ptr<Material> createMaterial(const std::string& type, const ParamSet& ps, const TextureRegistry& reg,
                                         const std::map<std::string, std::shared_ptr<Material>>& named, const std::string&) {
    const SpectrumKind A = SpectrumKind::Albedo, U = SpectrumKind::Unbounded;
    std::shared_ptr<Material> m;
    if (ps.has("normalmap")) {
        ps.getString("normalmap", "");
        warning(ps.loc, "\"normalmap\" is not supported yet; ignored");
    }
    if (ps.has("displacement")) {
        ps.getTexture("displacement");
        ps.getFloat("displacement", 0);
        warning(ps.loc, "material \"displacement\" (bump mapping) is not supported yet; ignored");
    }
    if (type == "diffuse") {
        m = std::make_shared<DiffuseMaterial>(spectrumParam(ps, "reflectance", Spectrum(0.5f), A, reg));
    } else if (type == "conductor" || type == "coatedconductor") {
        std::string pre = type == "coatedconductor" ? "conductor." : "";
        if (type == "coatedconductor")
            warning(ps.loc, "material \"coatedconductor\" is not supported yet; rendering its conductor layer only");
        SpectrumTex refl = spectrumParam(ps, pre + "reflectance", std::nullopt, A, reg);
        SpectrumTex eta = spectrumParam(ps, pre + "eta", std::nullopt, U, reg);
        SpectrumTex k = spectrumParam(ps, pre + "k", std::nullopt, U, reg);
        if (refl && (eta || k)) throw InputError(ps.loc, "conductor: give either \"reflectance\" or \"eta\"/\"k\", not both");
        if (!refl) {
            if (!eta) eta = std::make_shared<ConstantTexture<Spectrum>>(*namedSpectrumToRGB("metal-Cu-eta", U));
            if (!k) k = std::make_shared<ConstantTexture<Spectrum>>(*namedSpectrumToRGB("metal-Cu-k", U));
        }
        Roughness r = roughness(ps, reg, pre);
        if (type == "coatedconductor") {
            roughness(ps, reg, "interface.");
            ps.getFloat("interface.eta", 1.5f);
            ps.getFloat("thickness", 0.01f);
        }
        m = std::make_shared<ConductorMaterial>(eta, k, refl, r);
    } else if (type == "dielectric") {
        float eta = etaParam(ps, "eta");
        m = std::make_shared<DielectricMaterial>(eta, roughness(ps, reg));
    } else if (type == "thindielectric") {
        m = std::make_shared<ThinDielectricMaterial>(etaParam(ps, "eta"));
    } else if (type == "diffusetransmission") {
        m = std::make_shared<DiffuseTransmissionMaterial>(spectrumParam(ps, "reflectance", Spectrum(0.25f), A, reg),
                                                          spectrumParam(ps, "transmittance", Spectrum(0.25f), A, reg),
                                                          ps.getFloat("scale", 1));
    } else if (type == "coateddiffuse") {
        CoatedDiffuseParams p;
        p.reflectance = spectrumParam(ps, "reflectance", Spectrum(0.5f), A, reg);
        p.albedo = spectrumParam(ps, "albedo", Spectrum(0.0f), A, reg);
        p.roughness = roughness(ps, reg);
        p.thickness = floatParam(ps, "thickness", 0.01f, reg);
        p.g = floatParam(ps, "g", 0, reg);
        p.eta = etaParam(ps, "eta");
        p.maxDepth = std::clamp(ps.getInt("maxdepth", 10), 1, 100);
        p.nSamples = std::clamp(ps.getInt("nsamples", 1), 1, 64);
        if (ps.has("albedo")) warning(ps.loc, "coateddiffuse: scattering inside the layer (\"albedo\") is not supported; it is ignored");
        m = std::make_shared<CoatedDiffuseMaterial>(p);
    } else if (type == "mix") {
        std::vector<std::string> names = ps.getStrings("materials");
        if (names.size() != 2) throw InputError(ps.loc, "mix: \"string materials\" must name exactly two materials");
        std::array<std::shared_ptr<Material>, 2> ms;
        for (int i = 0; i < 2; ++i) {
            auto it = named.find(names[i]);
            if (it == named.end()) throw InputError(ps.loc, "mix: material \"" + names[i] + "\" is not defined");
            if (it->second->isInterface()) throw InputError(ps.loc, "mix: \"interface\" cannot be mixed");
            ms[i] = it->second;
        }
        m = std::make_shared<MixMaterial>(ms, floatParam(ps, "amount", 0.5f, reg));
    } else if (type == "interface" || type == "" || type == "none") {
        m = std::make_shared<InterfaceMaterial>();
    } else {
        warning(ps.loc, "material \"" + type + "\" is not supported; using diffuse 0.5");
        return std::make_shared<DiffuseMaterial>(std::make_shared<ConstantTexture<Spectrum>>(Spectrum(0.5f)));
    }
    ps.reportUnused("Material \"" + type + "\"");
    return m;
}

}  // namespace ps
