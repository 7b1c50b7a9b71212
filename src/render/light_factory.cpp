#include "image/image.h"
#include "lights/delta_lights.h"
#include "lights/goniometric_light.h"
#include "lights/infinite_lights.h"
#include "lights/projection_light.h"
#include "math/equal_area.h"
#include "render/light_image.h"
#include "render/scene_builder.h"

namespace ps {

namespace {

// pbrt-v4's default emission is the colour space's illuminant: white, luminance 1.
LightSpectrum emission(const ParamSet& ps, const char* name) {
    const RGBColorSpace& space = ps.colorSpace ? *ps.colorSpace : srgbColorSpace();
    auto rgb = ps.getSpectrum(name, SpectrumKind::Illuminant);
    if (!rgb) return LightSpectrum(Spectrum(1.0f), SpectrumSource::rgbIlluminant(space, {1, 1, 1}));
    return LightSpectrum(*rgb, *ps.getSpectrumSource(name, SpectrumKind::Illuminant));
}

std::unique_ptr<Light> createInfinite(const LightEntity& e, const std::string& base) {
    const ParamSet& ps = e.params;
    float scale = ps.getFloat("scale", 1);
    float E = ps.getFloat("illuminance", -1);
    std::string file = ps.getString("filename", "");
    if (ps.has("portal")) {
        ps.getPoint3s("portal");
        warning(e.loc, "infinite light: \"portal\" is not supported; the light is rendered without it");
    }
    if (file.empty()) {
        LightSpectrum L = emission(ps, "L");
        if (E > 0) scale *= E / kPi;  // uniform radiance L gives illuminance pi*L
        return std::make_unique<UniformInfiniteLight>(L * scale);
    }
    if (ps.has("L")) throw InputError(e.loc, "infinite light: cannot have both \"L\" and \"filename\"");
    Image img = readNamedBy(e.loc, [&] { return readImage(resolvePath(base, file)); });
    ImageInfiniteLight::Layout layout;
    if (img.width == img.height) {
        layout = ImageInfiniteLight::Layout::EqualArea;
    } else if (img.width == 2 * img.height) {
        layout = ImageInfiniteLight::Layout::LatLong;
        warning(e.loc, "infinite light \"" + file +
                           "\": 2:1 latitude-longitude map (z up) accepted; pbrt-v4 itself requires square equal-area maps");
    } else {
        throw InputError(e.loc, "infinite light \"" + file + "\": image is " + std::to_string(img.width) + "x" +
                                    std::to_string(img.height) + "; expected a square equal-area map or a 2:1 latitude-longitude map");
    }
    if (E > 0 && layout == ImageInfiniteLight::Layout::EqualArea) {
        // pbrt-v4's normalisation, reproduced exactly (it delivers about 2E; PBRT-CONVENTIONS §3).
        double sum = 0;
        for (int y = 0; y < img.height; ++y)
            for (int x = 0; x < img.width; ++x) {
                Vec2 uv((x + 0.5f) / img.width, (y + 0.5f) / img.height);
                Vec3 w = equalAreaSquareToSphere(uv);
                if (w.z > 0) sum += img.get(x, y).luminance() * w.z;
            }
        double k = 2 * kPi / (double(img.width) * img.height) * sum;
        if (k > 0) scale *= float(E / k);
    }
    return std::make_unique<ImageInfiniteLight>(std::move(img), scale, e.worldFromLight, layout);
}

// pbrt-v4's semantics: the image's mean of R, G, B per texel; "power" P divides by
// 4 pi times the mean texel (and keeps the RGB multiplier of I, as for point lights).
std::unique_ptr<Light> createGoniometric(const LightEntity& e, const std::string& base) {
    const ParamSet& ps = e.params;
    LightSpectrum I = emission(ps, "I");
    float scale = ps.getFloat("scale", 1);
    float P = ps.getFloat("power", -1);
    std::string file = ps.getString("filename", "");
    std::vector<float> values{1.0f};
    int res = 1;
    if (file.empty()) {
        warning(e.loc, "goniometric light: no \"filename\"; it emits I equally in every direction");
    } else {
        auto img = readLightImage(e.loc, base, file, "goniometric light");
        if (img->width != img->height)
            throw InputError(e.loc, "goniometric light " + quoteForMessage(file) + ": the image is " +
                                        std::to_string(img->width) + "x" + std::to_string(img->height) +
                                        "; it must be square (an equal-area octahedral map)");
        res = img->width;
        values.resize(size_t(res) * res);
        for (int y = 0; y < res; ++y)
            for (int x = 0; x < res; ++x) {
                Spectrum c = img->get(x, y);
                values[size_t(y) * res + x] = (c.r + c.g + c.b) / 3;
            }
    }
    if (P > 0) {
        double sum = 0;
        for (float v : values) sum += v;
        double k = 4 * kPi * sum / double(values.size());
        if (k > 0) scale *= float(P / k);
    }
    return std::make_unique<GoniometricLight>(e.worldFromLight, I * scale, std::move(values), res);
}

// pbrt-v4's semantics: "filename" is required; "power" P divides by the luminance of the
// texels times the solid angle each subtends (at its centre).
std::unique_ptr<Light> createProjection(const LightEntity& e, const std::string& base) {
    const ParamSet& ps = e.params;
    float scale = ps.getFloat("scale", 1);
    float P = ps.getFloat("power", -1);
    float fov = ps.getFloat("fov", 90);
    std::string file = ps.getString("filename", "");
    if (file.empty()) throw InputError(e.loc, "projection light: \"filename\" is required");
    if (!(fov > 0 && fov < 180)) {
        const Param* p = ps.find("fov");
        throw InputError(p ? p->loc : e.loc, "projection light: \"fov\" must be between 0 and 180 degrees");
    }
    auto img = readLightImage(e.loc, base, file, "projection light");
    if (P > 0) {
        ProjectionLight::Screen screen = ProjectionLight::screenFor(img->width, img->height, fov);
        double sum = 0;
        for (int y = 0; y < img->height; ++y)
            for (int x = 0; x < img->width; ++x)
                sum += img->get(x, y).luminance() * screen.texelCos3(x, y, img->width, img->height);
        double k = screen.planeArea() * sum / (double(img->width) * img->height);
        if (k > 0) scale *= float(P / k);
    }
    return std::make_unique<ProjectionLight>(e.worldFromLight, *img, scale, fov);
}

}  // namespace

std::unique_ptr<Light> createLight(const LightEntity& e, const std::string& base) {
    const ParamSet& ps = e.params;
    const Transform& T = e.worldFromLight;
    std::unique_ptr<Light> light;
    if (e.type == "point") {
        LightSpectrum I = emission(ps, "I");
        float scale = ps.getFloat("scale", 1);
        float P = ps.getFloat("power", -1);
        if (P > 0) scale *= P / (4 * kPi);
        light = std::make_unique<PointLight>(T.point(ps.getPoint3("from", {0, 0, 0})), I * scale);
    } else if (e.type == "spot") {
        LightSpectrum I = emission(ps, "I");
        float scale = ps.getFloat("scale", 1);
        float P = ps.getFloat("power", -1);
        float cone = ps.getFloat("coneangle", 30), delta = ps.getFloat("conedeltaangle", 5);
        float cosEnd = std::cos(radians(cone)), cosStart = std::cos(radians(cone - delta));
        if (P > 0) scale *= P / (2 * kPi * ((1 - cosStart) + (cosStart - cosEnd) / 2));
        Vec3 from = ps.getPoint3("from", {0, 0, 0}), to = ps.getPoint3("to", {0, 0, 1});
        Vec3 axis = T.vector(to - from);
        if (!(lengthSquared(axis) > 0)) throw InputError(e.loc, "spot light: \"from\" and \"to\" coincide");
        light = std::make_unique<SpotLight>(T.point(from), axis, I * scale, cosStart, cosEnd);
    } else if (e.type == "distant") {
        LightSpectrum L = emission(ps, "L");
        float scale = ps.getFloat("scale", 1);
        float E = ps.getFloat("illuminance", -1);
        if (E > 0) scale *= E;
        Vec3 from = ps.getPoint3("from", {0, 0, 0}), to = ps.getPoint3("to", {0, 0, 1});
        Vec3 w = T.vector(from - to);
        if (!(lengthSquared(w) > 0)) throw InputError(e.loc, "distant light: \"from\" and \"to\" coincide");
        light = std::make_unique<DistantLight>(normalize(w), L * scale);
    } else if (e.type == "infinite") {
        light = createInfinite(e, base);
    } else if (e.type == "goniometric") {
        light = createGoniometric(e, base);
    } else if (e.type == "projection") {
        light = createProjection(e, base);
    } else {
        // As pbrt-v4: a misspelt type would silently remove the light from the scene.
        throw InputError(e.loc, "LightSource \"" + e.type +
                                    "\": unknown light type (point, spot, distant, infinite, goniometric, projection)");
    }
    ps.reportUnused("LightSource \"" + e.type + "\"");
    return light;
}

}  // namespace ps
