#include "media/create_medium.h"

#include "media/cloud_medium.h"
#include "media/grid_medium.h"
#include "media/nanovdb_medium.h"
#include "media/homogeneous_medium.h"
#include "materials/named_scattering.h"
#include "util/error.h"
#include "util/path.h"

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

MediumBox boxOf(const MediumEntity& e) {
    MediumBox box{e.worldFromMedium.inverse(), e.params.getPoint3("p0", {0, 0, 0}), e.params.getPoint3("p1", {1, 1, 1})};
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

// pbrt-v4's "scale" of sigma_a and sigma_s (not read by "cloud", which has none).
float scaleParam(const MediumEntity& e) {
    const float scale = e.params.getFloat("scale", 1);
    // A negative coefficient has no meaning and would make the majorant's flights run backwards.
    if (!(scale >= 0) || !std::isfinite(scale)) fail(e, "\"scale\" must be a finite number at least 0");
    return scale;
}

// pbrt-v4's CloudMedium::Create: density 1, wispiness 1, frequency 5, sigma_a = sigma_s = 1,
// the box p0..p1 (0,0,0)..(1,1,1). It has no "scale" and no emission.
std::unique_ptr<Medium> createCloud(const MediumEntity& e, float g) {
    const ParamSet& ps = e.params;
    CloudMedium::Shape shape;
    shape.density = ps.getFloat("density", 1);
    shape.wispiness = ps.getFloat("wispiness", 1);
    shape.frequency = ps.getFloat("frequency", 5);
    if (!std::isfinite(shape.density) || !std::isfinite(shape.wispiness) || !std::isfinite(shape.frequency))
        fail(e, "\"density\", \"wispiness\" and \"frequency\" must be finite numbers");
    auto medium = std::make_unique<CloudMedium>(boxOf(e), spectrumParam(ps, "sigma_a", SpectrumKind::Unbounded, 1, 1),
                                                spectrumParam(ps, "sigma_s", SpectrumKind::Unbounded, 1, 1), g, shape);
    ps.reportUnused("medium " + quoteForMessage(e.name));
    return medium;
}

// pbrt-v4's NanoVDBMedium::Create: "filename" (required), the float grid "gridname"
// ("density"), sigma_a, sigma_s (1) times "scale" (1), g; and emission from the float grid
// "temperaturename" ("temperature") if the file has one and "Lescale" (1) > 0, its values
// mapped to kelvin by "temperatureoffset" (or its older name "temperaturecutoff"; 0) and
// "temperaturescale" (1) (nanovdb_medium.h).
std::unique_ptr<Medium> createNanoVDB(const MediumEntity& e, float g) {
    const ParamSet& ps = e.params;
    const std::string file = ps.getString("filename", "");
    if (file.empty()) fail(e, "a \"nanovdb\" medium needs a \"filename\"");
    const std::string path = resolvePath(ps.baseDirectory, file);
    const std::string gridName = ps.getString("gridname", "density");
    const bool namedTemperature = ps.has("temperaturename");
    const std::string temperatureName = ps.getString("temperaturename", "temperature");
    NanoVDBTemperature t;
    t.LeScale = ps.getFloat("Lescale", 1);
    t.offset = ps.getFloat("temperatureoffset", ps.getFloat("temperaturecutoff", 0));
    t.scale = ps.getFloat("temperaturescale", 1);
    if (!(t.LeScale >= 0) || !std::isfinite(t.LeScale)) fail(e, "\"Lescale\" must be a finite number at least 0");
    if (!std::isfinite(t.offset) || !std::isfinite(t.scale))
        fail(e, "\"temperatureoffset\" and \"temperaturescale\" must be finite numbers");
    const float scale = scaleParam(e);
    std::optional<NanoVDBGrid> density, temperature;
    try {
        density = readNanoVDBGrid(path, gridName);
        if (!density) fail(e, path + ": the file has no grid named " + quoteForMessage(gridName));
        // Without a temperature grid the medium does not emit (pbrt-v4), unless the scene
        // named one that is not there: then it is a mistake worth stopping for.
        temperature = readNanoVDBGrid(path, temperatureName);
        if (!temperature && namedTemperature)
            fail(e, path + ": the file has no grid named " + quoteForMessage(temperatureName) + " (\"temperaturename\")");
    } catch (const std::runtime_error& err) {
        if (dynamic_cast<const InputError*>(&err)) throw;
        fail(e, err.what());
    }
    std::optional<NanoVDBTemperature> emission;
    if (temperature && t.LeScale > 0) {
        t.grid = std::move(*temperature);
        emission = std::move(t);
    }
    auto medium = std::make_unique<NanoVDBMedium>(e.worldFromMedium, std::move(*density),
                                                  spectrumParam(ps, "sigma_a", SpectrumKind::Unbounded, 1, scale),
                                                  spectrumParam(ps, "sigma_s", SpectrumKind::Unbounded, 1, scale), g,
                                                  std::move(emission));
    ps.reportUnused("medium " + quoteForMessage(e.name));
    return medium;
}

}  // namespace

std::unique_ptr<Medium> createMedium(const MediumEntity& e) {
    const ParamSet& ps = e.params;
    const float g = ps.getFloat("g", 0);
    if (e.type == "cloud") return createCloud(e, g);
    if (e.type == "nanovdb") return createNanoVDB(e, g);
    const float scale = scaleParam(e);
    if (e.type == "homogeneous") {
        // pbrt-v4: a "preset" names measured coefficients (the subsurface material's table),
        // which replace sigma_a and sigma_s; an unknown one warns and leaves them.
        const std::string preset = ps.getString("preset", "");
        std::optional<NamedScattering> named = preset.empty() ? std::nullopt : namedScattering(preset);
        if (!preset.empty() && !named)
            warning(ps.find("preset")->loc, "MakeNamedMedium " + quoteForMessage(e.name) + ": no measured medium is named " +
                                                quoteForMessage(preset) + "; using \"sigma_a\" and \"sigma_s\" (known: " +
                                                namedScatteringList() + ")");
        if (named) {
            auto medium = std::make_unique<HomogeneousMedium>(srgbCoefficient(named->sigmaA, scale), srgbCoefficient(named->sigmaS, scale),
                                                              emissionParam(ps, ps.getFloat("Lescale", 1)), g);
            ps.reportUnused("medium " + quoteForMessage(e.name));
            return medium;
        }
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
        std::vector<Spectrum> a = rgbValues(e, "sigma_a", scale), s = rgbValues(e, "sigma_s", scale);
        if (a.empty() && s.empty()) fail(e, "an \"rgbgrid\" medium needs \"sigma_a\" and/or \"sigma_s\" values");
        // pbrt-v4's RGBGridMedium: "Le" is a grid of RGB illuminants, one per voxel like the
        // sigma grids, scaled by a single "Lescale" (1); emission needs a sigma_a grid (it is
        // sigma_a Le that the medium emits).
        std::vector<Spectrum> le = rgbValues(e, "Le", 1);
        const float LeScale = ps.getFloat("Lescale", 1);
        if (!le.empty() && a.empty()) fail(e, "\"Le\" needs a \"sigma_a\" grid (the medium emits sigma_a Le)");
        if (!(LeScale >= 0) || !std::isfinite(LeScale)) fail(e, "\"Lescale\" must be a finite number at least 0");
        VoxelGrid<Spectrum> ga, gs, gl;
        if (!a.empty()) ga = gridOf(e, std::move(a), "sigma_a");
        if (!s.empty()) gs = gridOf(e, std::move(s), "sigma_s");
        if (!le.empty()) gl = gridOf(e, std::move(le), "Le");
        auto medium = std::make_unique<GridMedium>(boxOf(e), std::move(ga), std::move(gs), ps.colorSpace, g,
                                                   std::move(gl), LeScale);
        ps.reportUnused("medium " + quoteForMessage(e.name));
        return medium;
    }
    fail(e, "unknown medium type " + quoteForMessage(e.type) + " (expected homogeneous, uniformgrid, rgbgrid, cloud or nanovdb)");
}

}  // namespace ps
