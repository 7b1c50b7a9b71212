#include "media/create_medium.h"

#include "media/grid_medium.h"
#include "media/homogeneous_medium.h"
#include "util/error.h"

#include <cmath>

namespace ps {

namespace {

// A spectrum parameter in both colour modes, pbrt-v4's default `def` when absent.
MediumSpectrum spectrumParam(const ParamSet& ps, const std::string& name, SpectrumKind kind, float def, float scale) {
    if (auto rgb = ps.getSpectrum(name, kind)) return MediumSpectrum(*rgb * scale, *ps.getSpectrumSource(name, kind), scale);
    return MediumSpectrum(Spectrum(def * scale), SpectrumSource::constant(def), scale);
}

// Le over its photometric integral, as pbrt-v4 normalises a medium's emission like a light's.
MediumSpectrum emissionParam(const ParamSet& ps, float LeScale) {
    auto rgb = ps.getSpectrum("Le", SpectrumKind::Illuminant);
    if (!rgb) return {};
    SpectrumSource src = *ps.getSpectrumSource("Le", SpectrumKind::Illuminant);
    const double phi = src.photometric();
    if (!(phi > 0)) return {};
    // RGB mode keeps the RGB magnitude, as LightSpectrum does for lights.
    return MediumSpectrum(*rgb * LeScale, std::move(src), LeScale / float(phi));
}

[[noreturn]] void fail(const MediumEntity& e, const std::string& msg) {
    throw InputError(e.loc, "MakeNamedMedium " + quoteForMessage(e.name) + ": " + msg);
}

template <typename T>
VoxelGrid<T> gridOf(const MediumEntity& e, std::vector<T> values, const char* what) {
    VoxelGrid<T> g;
    g.nx = e.params.getInt("nx", 1);
    g.ny = e.params.getInt("ny", 1);
    g.nz = e.params.getInt("nz", 1);
    if (g.nx < 1 || g.ny < 1 || g.nz < 1) fail(e, "\"nx\", \"ny\" and \"nz\" must be at least 1");
    const size_t n = size_t(g.nx) * size_t(g.ny) * size_t(g.nz);
    if (values.size() != n)
        fail(e, std::string("the grid has ") + std::to_string(values.size()) + " \"" + what + "\" values; expected nx*ny*nz = " +
                    std::to_string(g.nx) + "*" + std::to_string(g.ny) + "*" + std::to_string(g.nz) + " = " + std::to_string(n));
    g.values = std::move(values);
    return g;
}

GridMedium::Box boxOf(const MediumEntity& e) {
    GridMedium::Box box{e.worldFromMedium, e.params.getPoint3("p0", {0, 0, 0}), e.params.getPoint3("p1", {1, 1, 1})};
    if (!(box.p1.x > box.p0.x && box.p1.y > box.p0.y && box.p1.z > box.p0.z))
        fail(e, "\"p1\" must exceed \"p0\" in every coordinate");
    return box;
}

std::vector<Spectrum> rgbValues(const MediumEntity& e, const std::string& name, float scale) {
    const Param* p = e.params.find(name);
    if (!p) return {};
    p->used = true;
    if (p->type != ParamType::RGB || p->numbers.size() % 3 != 0) fail(e, "\"" + name + "\" must be an \"rgb\" array");
    std::vector<Spectrum> v;
    for (size_t i = 0; i < p->numbers.size(); i += 3) {
        Spectrum s(float(p->numbers[i]), float(p->numbers[i + 1]), float(p->numbers[i + 2]));
        if (s.r < 0 || s.g < 0 || s.b < 0) fail(e, "\"" + name + "\" values must not be negative");
        v.push_back(s * scale);
    }
    return v;
}

}  // namespace

std::unique_ptr<Medium> createMedium(const MediumEntity& e) {
    const ParamSet& ps = e.params;
    const float g = ps.getFloat("g", 0);
    const float scale = ps.getFloat("scale", 1);
    // A negative coefficient has no meaning and would make the majorant's flights run backwards.
    if (!(scale >= 0) || !std::isfinite(scale)) fail(e, "\"scale\" must be a finite number at least 0");
    if (e.type == "homogeneous") {
        if (ps.has("preset"))
            fail(e, "named \"preset\" media (" + quoteForMessage(ps.getString("preset", "")) +
                        ") are not supported yet; give \"sigma_a\" and \"sigma_s\"");
        auto medium = std::make_unique<HomogeneousMedium>(spectrumParam(ps, "sigma_a", SpectrumKind::Unbounded, 1, scale),
                                                          spectrumParam(ps, "sigma_s", SpectrumKind::Unbounded, 1, scale),
                                                          emissionParam(ps, ps.getFloat("Lescale", 1)), g);
        ps.reportUnused("medium " + quoteForMessage(e.name));
        return medium;
    }
    if (e.type == "uniformgrid") {
        std::vector<float> density = ps.getFloats("density");
        if (density.empty()) fail(e, "a \"uniformgrid\" medium needs \"density\" values");
        for (float v : density)
            if (!(v >= 0) || !std::isfinite(v)) fail(e, "\"density\" values must be finite and at least 0");
        if (ps.has("temperature")) fail(e, "\"temperature\" grids are not supported yet");
        VoxelGrid<float> dg = gridOf(e, std::move(density), "density");
        VoxelGrid<float> le;
        std::vector<float> leScale = ps.getFloats("Lescale");
        if (leScale.empty()) le.values = {1.0f};
        else le = gridOf(e, std::move(leScale), "Lescale");
        auto medium = std::make_unique<GridMedium>(boxOf(e), std::move(dg), spectrumParam(ps, "sigma_a", SpectrumKind::Unbounded, 1, scale),
                                                   spectrumParam(ps, "sigma_s", SpectrumKind::Unbounded, 1, scale),
                                                   emissionParam(ps, 1), std::move(le), g);
        ps.reportUnused("medium " + quoteForMessage(e.name));
        return medium;
    }
    if (e.type == "rgbgrid") {
        if (ps.has("Le")) fail(e, "emission (\"Le\") in an \"rgbgrid\" medium is not supported yet");
        std::vector<Spectrum> a = rgbValues(e, "sigma_a", scale), s = rgbValues(e, "sigma_s", scale);
        if (a.empty() && s.empty()) fail(e, "an \"rgbgrid\" medium needs \"sigma_a\" and/or \"sigma_s\" values");
        VoxelGrid<Spectrum> ga, gs;
        if (!a.empty()) ga = gridOf(e, std::move(a), "sigma_a");
        if (!s.empty()) gs = gridOf(e, std::move(s), "sigma_s");
        auto medium = std::make_unique<GridMedium>(boxOf(e), std::move(ga), std::move(gs), ps.colorSpace, g);
        ps.reportUnused("medium " + quoteForMessage(e.name));
        return medium;
    }
    if (e.type == "cloud" || e.type == "nanovdb")
        fail(e, "medium type " + quoteForMessage(e.type) +
                    " is not supported yet (homogeneous, uniformgrid and rgbgrid are); rendering without it would remove the scene's subject");
    fail(e, "unknown medium type " + quoteForMessage(e.type) + " (expected homogeneous, uniformgrid, rgbgrid, cloud or nanovdb)");
}

}  // namespace ps
