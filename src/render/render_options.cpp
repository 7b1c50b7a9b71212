// Camera, film, filter, sampler and integrator directives -> Scene settings.
#include <cmath>
#include <limits>

#include "render/realistic_camera_options.h"
#include "render/scene_builder.h"
#include "scene/color_space.h"

namespace ps {

namespace {

SphericalMapping sphericalMapping(const ParamSet& ps, const SourceLoc& cameraLoc) {
    std::string m = ps.getString("mapping", "equalarea");
    if (m == "equalarea") return SphericalMapping::EqualArea;
    if (m == "equirectangular") return SphericalMapping::Equirectangular;
    const Param* p = ps.find("mapping");
    throw InputError(p ? p->loc : cameraLoc,
                     "Camera \"spherical\": unknown \"mapping\" \"" + m + "\" (must be \"equalarea\" or \"equirectangular\")");
}

void applyCamera(const SceneDescription& desc, Scene& scene, int xRes, int yRes, float filmDiagonalMm) {
    const CameraEntity& c = desc.camera;
    const ParamSet& ps = c.params;
    Camera::Params p;
    p.worldFromCamera = c.worldFromCamera;
    p.xRes = xRes;
    p.yRes = yRes;
    if (c.type == "orthographic") {
        p.projection = Camera::Projection::Orthographic;
    } else if (c.type == "spherical") {
        p.projection = Camera::Projection::Spherical;
        p.mapping = sphericalMapping(ps, c.loc);
    } else if (c.type == "realistic") {
        p.projection = Camera::Projection::Realistic;
        p.lens = createLensSystem(ps, c.loc, desc.baseDirectory, filmDiagonalMm, xRes, yRes);
    } else if (c.type != "perspective") {
        warning(c.loc, "Camera \"" + c.type + "\" is not supported; using \"perspective\"");
    }
    if (p.projection == Camera::Projection::Perspective) {
        p.fovDeg = ps.getFloat("fov", 90);
        if (!(p.fovDeg > 0 && p.fovDeg < 180)) throw InputError(c.loc, "Camera: \"fov\" must be in (0, 180) degrees");
    }
    // The spherical camera accepts the lens and screen parameters and ignores them (a pinhole
    // seeing the whole sphere), as pbrt-v4 does; its "fov" stays unused and is reported.
    // The realistic camera ignores them too: its lens system is its whole projection.
    p.lensRadius = ps.getFloat("lensradius", 0);
    p.focalDistance = ps.getFloat("focaldistance", 1e6f);
    if (p.projection == Camera::Projection::Spherical || p.projection == Camera::Projection::Realistic) p.lensRadius = 0;
    std::vector<float> sw = ps.getFloats("screenwindow");
    if (sw.size() == 4) {
        for (int i = 0; i < 4; ++i) p.screenWindow[i] = sw[i];
    } else if (!sw.empty()) {
        throw InputError(c.loc, "Camera: \"screenwindow\" needs 4 values");
    }
    float frame = ps.getFloat("frameaspectratio", -1);
    if (frame > 0 && sw.empty()) {
        if (frame > 1) {
            p.screenWindow[0] = -frame; p.screenWindow[1] = frame; p.screenWindow[2] = -1; p.screenWindow[3] = 1;
        } else {
            p.screenWindow[0] = -1; p.screenWindow[1] = 1; p.screenWindow[2] = -1 / frame; p.screenWindow[3] = 1 / frame;
        }
    }
    float open = ps.getFloat("shutteropen", 0), close = ps.getFloat("shutterclose", 1);
    scene.settings().imagingRatio *= (close - open);
    p.shutterOpen = open;
    p.shutterClose = close;
    p.motion = AnimatedTransform(c.worldFromCamera, c.transformStartTime, c.worldFromCameraEnd, c.transformEndTime);
    scene.settings().cameraLoc = c.loc;
    scene.setCamera(std::make_unique<Camera>(p));
    ps.reportUnused("Camera \"" + c.type + "\"");
}

PixelBounds computeBounds(const ParamSet& ps, const SourceLoc& loc, int xRes, int yRes) {
    PixelBounds b{0, xRes, 0, yRes};
    std::vector<float> crop = ps.getFloats("cropwindow");
    std::vector<int> pb = ps.getInts("pixelbounds");
    if (!pb.empty()) {
        if (pb.size() != 4) throw InputError(loc, "Film: \"pixelbounds\" needs 4 values");
        b = {std::max(0, pb[0]), std::min(xRes, pb[1]), std::max(0, pb[2]), std::min(yRes, pb[3])};
    } else if (!crop.empty()) {
        if (crop.size() != 4) throw InputError(loc, "Film: \"cropwindow\" needs 4 values");
        b = cropWindowToPixels(xRes, yRes, crop.data());
    }
    if (b.width() <= 0 || b.height() <= 0) throw InputError(loc, "Film: the crop window is empty");
    return b;
}

std::unique_ptr<Filter> createFilter(const SceneEntity& f) {
    const ParamSet& ps = f.params;
    std::unique_ptr<Filter> filter;
    auto radius = [&](float def) { return Vec2(ps.getFloat("xradius", def), ps.getFloat("yradius", def)); };
    std::string type = f.type;
    if (type != "box" && type != "gaussian" && type != "triangle" && type != "mitchell") {
        warning(f.loc, "PixelFilter \"" + type + "\" is not supported; using \"gaussian\"");
        type = "gaussian";
    }
    Vec2 r;
    if (type == "box") {
        r = radius(0.5f);
    } else if (type == "gaussian") {
        r = radius(1.5f);
    } else {
        r = radius(2.0f);
    }
    if (!(r.x > 0 && r.y > 0 && r.x < 64 && r.y < 64))
        throw InputError(f.loc, "PixelFilter: radius must be in (0, 64)");
    if (type == "box") filter = std::make_unique<BoxFilter>(r);
    else if (type == "triangle") filter = std::make_unique<TriangleFilter>(r);
    else if (type == "mitchell") filter = std::make_unique<MitchellFilter>(r, ps.getFloat("B", 1.f / 3), ps.getFloat("C", 1.f / 3));
    else {
        float sigma = ps.getFloat("sigma", 0.5f);
        if (!(sigma > 0)) throw InputError(f.loc, "PixelFilter \"gaussian\": \"sigma\" must be positive");
        filter = std::make_unique<GaussianFilter>(r, sigma);
    }
    if (f.type == type) ps.reportUnused("PixelFilter \"" + type + "\"");
    return filter;
}

}  // namespace

void applyRenderOptions(const SceneDescription& desc, Scene& scene) {
    RenderSettings& s = scene.settings();

    // Film.
    const ParamSet& film = desc.film.params;
    // pbrt-v4's other films write the rgb film's image plus more layers: "gbuffer" geometric
    // ones (position, normals, albedo, variance), "spectral" per-wavelength buckets. Rendered
    // as "rgb" with one warning saying what is missing; their own parameters are read so that
    // they do not warn again as unused.
    if (desc.film.type == "gbuffer") {
        film.getString("coordinatesystem", "camera");
        warning(desc.film.loc, "Film \"gbuffer\" is rendered as \"rgb\": only the RGB image is written, without "
                               "the geometric layers (position, normals, albedo, variance)");
    } else if (desc.film.type == "spectral") {
        film.getInt("nbuckets", 16);
        film.getFloat("lambdamin", 360);
        film.getFloat("lambdamax", 830);
        warning(desc.film.loc, "Film \"spectral\" is rendered as \"rgb\": only the RGB image is written, without "
                               "the per-wavelength layers");
    } else if (desc.film.type != "rgb") {
        warning(desc.film.loc, "Film \"" + desc.film.type + "\" is not a film type of pbrt-v4; using \"rgb\"");
    }
    int xRes = film.getInt("xresolution", 1280), yRes = film.getInt("yresolution", 720);
    // Only a guard for the arithmetic (pixel counts fit 40 bits); what a film may cost is the
    // memory limit's to say, once the render knows its integrator and threads.
    const int kMaxSide = 1 << 20;
    if (xRes <= 0 || yRes <= 0 || xRes > kMaxSide || yRes > kMaxSide)
        throw InputError(desc.film.loc, "Film: resolution " + std::to_string(xRes) + "x" + std::to_string(yRes) +
                                            " is out of range (each side from 1 to " + std::to_string(kMaxSide) + " pixels)");
    s.filmLoc = desc.film.loc;
    s.outputFile = film.getString("filename", "pbrt.exr");
    scene.setPixelBounds(computeBounds(film, desc.film.loc, xRes, yRes));
    if (film.colorSpace && film.colorSpace != &srgbColorSpace())
        s.outputColorMatrix = outputFromRenderingSpace(*film.colorSpace);
    s.filmColorSpace = film.colorSpace;
    float iso = film.getFloat("iso", 100);
    s.imagingRatio = iso / 100;
    film.getBool("savefp16", true);  // we always write float32 EXR
    const float diagonalMm = film.getFloat("diagonal", 35);  // only the realistic camera uses it
    s.whiteBalance = film.getFloat("whitebalance", 0);
    if (s.whiteBalance < 0) throw InputError(film.find("whitebalance")->loc, "Film: \"whitebalance\" must not be negative");
    if (s.whiteBalance != 0 && !s.spectral)
        warning(desc.film.loc, "Film: \"whitebalance\" is applied in spectral mode only (--color spectral)");
    if (film.getString("sensor", "cie1931") != "cie1931")
        warning(desc.film.loc, "Film: only the \"cie1931\" sensor is supported; using it");
    s.maxComponentValue = film.getFloat("maxcomponentvalue", std::numeric_limits<float>::infinity());
    if (!(s.maxComponentValue > 0)) {
        const Param* p = film.find("maxcomponentvalue");
        throw InputError(p ? p->loc : desc.film.loc, "Film: \"maxcomponentvalue\" must be positive");
    }
    film.reportUnused("Film \"" + desc.film.type + "\"");

    applyCamera(desc, scene, xRes, yRes, diagonalMm);
    scene.setFilter(createFilter(desc.filter));
    scene.camera().setFilterMargin(scene.filter().radius());

    // Sampler: pbrt-v4's names map to ours; its global "sobol" and "paddedsobol" both become
    // our padded Owen-scrambled Sobol, and "pmj02bn" (per-pixel (0,2)-sequences, padded) its
    // nearest relative, the same sampler.
    const ParamSet& sp = desc.sampler.params;
    const std::string& st = desc.sampler.type;
    s.spp = sp.getInt("pixelsamples", st == "independent" ? 4 : 16);
    s.seed = uint64_t(std::max(0, sp.getInt("seed", 0)));
    if (sp.getString("randomization", "") == "none")
        warning(desc.sampler.loc, "Sampler \"" + st + "\": \"randomization\" \"none\" is not supported; points are always randomised");
    if (st == "stratified") {
        if (!sp.getBool("jitter", true))
            warning(desc.sampler.loc, "Sampler \"stratified\": \"jitter\" false is not supported; samples are jittered");
        s.spp = sp.getInt("xsamples", 4) * sp.getInt("ysamples", 4);
    }
    if (desc.sampler.loc.line <= 0) {
        // No Sampler directive: pbrt's implied "zsobol" gives way to our default (RenderSettings).
    } else if (st == "halton" || st == "zsobol" || st == "stratified" || st == "independent") {
        s.sampler = st;
    } else {
        s.sampler = "sobol";
        if (st != "sobol" && st != "paddedsobol")
            warning(desc.sampler.loc, "Sampler \"" + st + "\" is not available; using the nearest, \"sobol\" (padded, Owen-scrambled)");
    }
    if (s.spp <= 0) throw InputError(desc.sampler.loc, "Sampler: \"pixelsamples\" must be positive");
    sp.reportUnused("Sampler \"" + st + "\"");

    // Integrator.
    const ParamSet& ip = desc.integrator.params;
    std::string it = desc.integrator.type;
    s.sceneIntegrator = it;
    s.maxDepth = ip.getInt("maxdepth", 5);
    if (s.maxDepth < 0) throw InputError(desc.integrator.loc, "Integrator: \"maxdepth\" must be >= 0");
    s.regularize = ip.getBool("regularize", false);
    // How next-event estimation chooses a light (lights/light_sampler.h); the path tracer uses
    // it, the other integrators choose by power for now.
    s.lightSampler = ip.getString("lightsampler", "bvh");
    if (s.lightSampler == "exhaustive") {
        // pbrt-v4's reference for "bvh" (every light's importance, no tree): the same kind of
        // choice, so its nearest relative.
        warning(ip.find("lightsampler")->loc, "Integrator: \"lightsampler\" \"exhaustive\" is not available; using \"bvh\"");
        s.lightSampler = "bvh";
    } else if (!isLightSamplerName(s.lightSampler)) {
        const Param* p = ip.find("lightsampler");
        throw InputError(p ? p->loc : desc.integrator.loc, "Integrator: unknown \"lightsampler\" " + quoteForMessage(s.lightSampler) +
                                                               " (must be " + kLightSamplerNames + ")");
    }
    bool known = true;
    if (it == "path" || it == "volpath") {
        s.integrator = "path";
    } else if (it == "bdpt") {
        s.integrator = "bdpt";
        // pbrt-v4's debugging outputs of single strategies are ours only on the command line.
        for (const char* p : {"visualizestrategies", "visualizeweights"})
            if (ip.getBool(p, false)) warning(desc.integrator.loc, std::string("Integrator \"bdpt\": \"") + p +
                                                                   "\" is not supported; use --bdpt-strategies");
    } else if (it == "lightpath") {
        s.integrator = "light";
    } else if (it == "pssmlt" || it == "mmlt" || it == "mlt") {
        // pbrt-v4's "mlt" is multiplexed MLT over BDPT: ours is "mmlt" (whose chains also move
        // between path depths, see transport/mlt/mmlt.h). "pssmlt" is Kelemen-style MLT over
        // BDPT. All three read pbrt-v4's "mlt" parameters.
        s.integrator = it == "pssmlt" ? "pssmlt" : "mmlt";
        // pbrt-v4's default for "mlt" is 100 mutations per pixel whatever the Sampler says.
        s.spp = ip.getInt("mutationsperpixel", it == "mlt" ? 100 : s.spp);
        s.mltBootstrapSamples = ip.getInt("bootstrapsamples", s.mltBootstrapSamples);
        s.mltChains = ip.getInt("chains", s.mltChains);
        s.mltLargeStepProbability = ip.getFloat("largestepprobability", s.mltLargeStepProbability);
        s.mltSigma = ip.getFloat("sigma", s.mltSigma);
        if (s.regularize) {
            warning(desc.integrator.loc, "Integrator \"" + it + "\": \"regularize\" true makes the image biased "
                                         "(it blurs near-specular paths); ignored");
            s.regularize = false;
        }
        if (s.spp < 1 || s.mltBootstrapSamples < 1 || s.mltChains < 1 || !(s.mltSigma > 0) ||
            !(s.mltLargeStepProbability >= 0 && s.mltLargeStepProbability <= 1))
            throw InputError(desc.integrator.loc, "Integrator \"" + it + "\": mutationsperpixel, bootstrapsamples and "
                                                  "chains must be >= 1, sigma > 0 and largestepprobability in [0, 1]");
    } else {
        known = false;
        warning(desc.integrator.loc, "Integrator \"" + it + "\" is not available yet; using \"path\"");
        s.integrator = "path";
    }
    if (known) ip.reportUnused("Integrator \"" + it + "\"");

    auto seedOpt = desc.options.find("seed");
    if (seedOpt != desc.options.end()) s.seed = std::strtoull(seedOpt->second.c_str(), nullptr, 10);
}

}  // namespace ps
