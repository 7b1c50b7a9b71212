#include "render/scene_builder.h"

#include "lights/bvh_light_sampler.h"
#include "lights/emission_choice.h"
#include "media/create_medium.h"
#include "media/homogeneous_medium.h"

#include <mutex>

#include "lights/area_light.h"
#include "materials/create.h"
#include "materials/subsurface_material.h"
#include "render/camera_medium_check.h"
#include "render/embree_motion.h"
#include "render/light_image.h"

namespace ps {

// Friend of Scene: assembles its private parts.
class SceneBuilder {
public:
    SceneBuilder(const SceneDescription& desc, Scene& scene) : desc_(desc), scene_(scene) {}
    void build();

private:
    void createMaterials();
    const Material* materialFor(const ShapeEntity& e) const;
    // MakeNamedMedium's media, all of them (pbrt-v4 creates every named medium), the camera's
    // medium and whether any shape bounds a medium.
    void createMedia();
    const Medium* mediumNamed(const std::string& name, const SourceLoc& loc) const;
    // The interior medium of a `subsurface` material, made once per material; null for others.
    const Medium* subsurfaceMedium(const Material* m);
    void assignMedia(const ShapeEntity& e, Shape& shape);
    void warnIfCameraMediumContradicted() const;
    // An `interface` shape is left out of the BVH unless it may bound a medium.
    bool skipped(const Shape& shape) const {
        return !scene_.hasMedia_ && shape.material && shape.material->isInterface();
    }
    void addAreaLights(const ShapeEntity& e, Shape& shape);
    void addWorldShapes();
    void addInstances();
    void addLights();
    unsigned attach(RTCScene target, const Shape& shape);
    // A new instance prototype holding def's shapes, each placed by prototypeFromInstance
    // times its own transform; returns its index.
    int buildPrototype(const InstanceDefinition& def, const Transform& prototypeFromInstance);
    // A moving shape (its CTM keyframes differ): alone in a prototype, instanced with motion.
    void addMovingShape(const ShapeEntity& e);
    // An instance of prototype `proto` in the world; `motion` (if animated) moves it, with
    // em its Embree form, and the prototype then holds geometry placed by em's C.
    void addInstance(int proto, const Transform& worldFromPrototype, const AnimatedTransform& motion,
                     const EmbreeMotion* em);
    AnimatedTransform motionOf(const Transform& start, const Transform& end) const {
        return AnimatedTransform(start, desc_.transformStartTime, end, desc_.transformEndTime);
    }

    const SceneDescription& desc_;
    Scene& scene_;
    TextureRegistry textures_;
    std::map<std::string, std::shared_ptr<Material>> named_;
    std::map<std::string, const Medium*> media_;
    std::map<const Material*, const Medium*> subsurfaceMedia_;
};

namespace {
// Robust traversal and intersection: without it rays through an edge two triangles share
// can miss both (6% of rays within 1e-6 of a quad's diagonal did), and a lit plane loses
// that light (tests/geometry/shared_edge_test.cpp).
constexpr RTCSceneFlags kSceneFlags = RTC_SCENE_FLAG_ROBUST;
std::mutex gEmbreeErrorMutex;
std::string gEmbreeError;
void embreeError(void*, RTCError code, const char* str) {
    if (code == RTC_ERROR_NONE) return;
    std::lock_guard<std::mutex> lock(gEmbreeErrorMutex);
    gEmbreeError = str ? str : "unknown Embree error";
}
}  // namespace

void SceneBuilder::createMaterials() {
    const std::string& base = desc_.baseDirectory;
    for (const TextureEntity& t : desc_.floatTextures)
        if (auto tex = createFloatTexture(t, textures_, base)) textures_.floats[t.name] = tex;
    for (const TextureEntity& t : desc_.spectrumTextures)
        if (auto tex = createSpectrumTexture(t, textures_, base)) textures_.spectra[t.name] = tex;

    // Named materials: `mix` refers to others, so create in rounds until all resolve.
    std::vector<const MaterialEntity*> pending;
    for (const auto& [name, m] : desc_.namedMaterials) pending.push_back(&m);
    while (!pending.empty()) {
        std::vector<const MaterialEntity*> next;
        for (const MaterialEntity* m : pending) {
            bool ready = true;
            if (m->type == "mix")
                for (const std::string& n : m->params.getStrings("materials"))
                    if (!named_.count(n)) ready = false;
            if (!ready) {
                next.push_back(m);
                continue;
            }
            named_[m->name] = createMaterial(m->type, m->params, textures_, named_, base, scene_.settings().spectral);
            named_[m->name]->label = "MakeNamedMaterial \"" + m->name + "\" (" + m->type + ") at " + m->loc.str();
        }
        if (next.size() == pending.size()) {
            const MaterialEntity* m = next.front();
            throw InputError(m->loc, "mix material " + quoteForMessage(m->name) + " refers to a material that is not defined");
        }
        pending = std::move(next);
    }
    for (const MaterialEntity& m : desc_.materials) {
        scene_.materials_.push_back(createMaterial(m.type, m.params, textures_, named_, base, scene_.settings().spectral));
        scene_.materials_.back()->label = "Material \"" + m.type + "\" at " + m.loc.str();
    }
    // The scene owns every material; shapes keep raw pointers.
    for (const auto& [name, m] : named_) scene_.materials_.push_back(m);
}

const Material* SceneBuilder::materialFor(const ShapeEntity& e) const {
    if (!e.material.name.empty()) {
        auto it = named_.find(e.material.name);
        if (it == named_.end()) throw InputError(e.loc, "this shape's NamedMaterial " + quoteForMessage(e.material.name) + " is not defined");
        return it->second.get();
    }
    if (e.material.index >= 0 && size_t(e.material.index) < scene_.materials_.size())
        return scene_.materials_[e.material.index].get();
    return scene_.materials_.empty() ? nullptr : scene_.materials_.front().get();
}

void SceneBuilder::addAreaLights(const ShapeEntity& e, Shape& shape) {
    if (e.areaLight < 0 || size_t(e.areaLight) >= desc_.areaLights.size()) return;
    const SceneEntity& al = desc_.areaLights[e.areaLight];
    if (shape.material && shape.material->isInterface()) {
        warning(e.loc, "area light on a shape with the \"interface\" material is ignored (as in pbrt-v4)");
        return;
    }
    if (al.type != "diffuse") {
        warning(al.loc, "AreaLightSource \"" + al.type + "\" is not supported; using \"diffuse\"");
    }
    const ParamSet& ps = al.params;
    float scale = ps.getFloat("scale", 1);
    bool twoSided = ps.getBool("twosided", false);
    float power = ps.getFloat("power", -1);
    // An emission image (pbrt-v4's "filename") replaces L: L multiplies its values by scale.
    std::string file = ps.getString("filename", "");
    std::shared_ptr<const EmissionImage> image;
    if (!file.empty()) {
        if (ps.has("L")) throw InputError(al.loc, "AreaLightSource \"diffuse\": cannot have both \"L\" and \"filename\"");
        image = std::make_shared<EmissionImage>(readLightImage(al.loc, desc_.baseDirectory, file, "area light"));
    }
    // pbrt-v4's default emission is the colour space's illuminant (white, luminance 1).
    const RGBColorSpace& space = ps.colorSpace ? *ps.colorSpace : srgbColorSpace();
    LightSpectrum L(Spectrum(1.0f), SpectrumSource::rgbIlluminant(space, {1, 1, 1}));
    if (!image)
        if (auto rgb = ps.getSpectrum("L", SpectrumKind::Illuminant))
            L = LightSpectrum(*rgb, *ps.getSpectrumSource("L", SpectrumKind::Illuminant));
    ps.reportUnused("AreaLightSource \"diffuse\"");
    // pbrt-v4 divides "power" by the image's mean luminance (a uniform L keeps its RGB factor).
    float powerDivisor = image ? image->meanLuminance() : 1.0f;
    shape.emissionNeedsUV = image != nullptr;
    shape.prepareSampling();
    int n = shape.primitiveCount();
    shape.areaLights.resize(n);
    for (int i = 0; i < n; ++i) {
        float s = scale;
        // pbrt-v4: power is per shape, and every triangle of a mesh is a shape.
        if (power > 0) {
            float a = shape.area(i);
            float k = kPi * (twoSided ? 2 : 1) * a * powerDivisor;
            s *= k > 0 ? power / k : 0.0f;
        }
        auto light = std::make_unique<DiffuseAreaLight>(&shape, i, L * s, twoSided, image);
        // Without a transition the shape lies in the current outside medium (pbrt-v4).
        light->mediumInside = shape.mediumTransition ? shape.mediumInside : mediumNamed(e.media.outside, e.media.loc);
        light->mediumOutside = shape.mediumTransition ? shape.mediumOutside : light->mediumInside;
        shape.areaLights[i] = light.get();
        scene_.lights_.push_back(std::move(light));
    }
}

// An `interface` shape only marks where a medium begins: it neither scatters nor emits, so
// no ray may stop at it. Without media it is left out of the geometry altogether (kept, it
// blocked every shadow and connection ray through it: the agreement matrix's Interface
// cells); with media it stays, and rays cross it changing medium (media/, path_tracer).
const Medium* SceneBuilder::mediumNamed(const std::string& name, const SourceLoc& loc) const {
    if (name.empty()) return nullptr;  // "" is vacuum
    auto it = media_.find(name);
    if (it == media_.end()) {
        std::string known;
        for (const auto& [n, m] : media_) known += (known.empty() ? "" : ", ") + quoteForMessage(n);
        throw InputError(loc, "MediumInterface: medium " + quoteForMessage(name) + " is not defined" +
                                  (known.empty() ? std::string(" (no MakeNamedMedium defines any)") : " (defined: " + known + ")"));
    }
    return it->second;
}

void SceneBuilder::createMedia() {
    for (const auto& [name, e] : desc_.media) {
        scene_.media_.push_back(createMedium(e));
        media_[name] = scene_.media_.back().get();
    }
    scene_.cameraMedium_ = mediumNamed(desc_.camera.medium, desc_.camera.mediumLoc);
    bool transitions = false;
    auto check = [&](const ShapeEntity& e) {
        // Both names resolve even when equal: an undefined name is an error wherever it is.
        mediumNamed(e.media.inside, e.media.loc);
        mediumNamed(e.media.outside, e.media.loc);
        transitions = transitions || e.media.transition() || subsurfaceMedium(materialFor(e));
    };
    for (const ShapeEntity& e : desc_.shapes) check(e);
    for (const auto& [n, def] : desc_.instances)
        for (const ShapeEntity& e : def.shapes) check(e);
    scene_.hasMedia_ = scene_.cameraMedium_ || transitions;
}

void SceneBuilder::warnIfCameraMediumContradicted() const {
    if (!scene_.hasMedia_) return;
    const std::optional<const Medium*> implied = mediumImpliedAt(scene_, scene_.camera().position());
    if (!implied || *implied == scene_.cameraMedium_) return;
    // A medium's name in the file; none for a subsurface material's (made by the builder).
    auto nameOf = [&](const Medium* m) -> const std::string* {
        for (const auto& [name, ptr] : media_)
            if (ptr == m) return &name;
        return nullptr;
    };
    auto named = [&](const Medium* m) {
        if (!m) return std::string("no medium");
        const std::string* name = nameOf(m);
        return name ? "medium \"" + *name + "\"" : std::string("the medium inside a \"subsurface\" material");
    };
    // Rendered as declared (pbrt-v4 does the same); the warning says how to declare the other.
    const std::string* impliedName = nameOf(*implied);
    const std::string fix = impliedName ? "; if the camera is meant to be in it, write MediumInterface \"" + *impliedName +
                                              "\" before Camera"
                                        : "";
    warning(desc_.camera.loc, "the camera is declared in " + named(scene_.cameraMedium_) +
                                  " (the outside medium of the MediumInterface current at Camera), but the "
                                  "medium boundaries around it enclose it in " + named(*implied) +
                                  ". Rays leave the camera in " + named(scene_.cameraMedium_) +
                                  " until they cross a boundary" + fix);
}

const Medium* SceneBuilder::subsurfaceMedium(const Material* m) {
    const auto* sss = dynamic_cast<const SubsurfaceMaterial*>(m);
    if (!sss) return nullptr;
    const Medium*& medium = subsurfaceMedia_[m];
    if (!medium) {
        const SubsurfaceInterior& in = sss->interior();
        scene_.media_.push_back(std::make_unique<HomogeneousMedium>(in.sigmaA, in.sigmaS, MediumSpectrum(), in.g));
        medium = scene_.media_.back().get();
    }
    return medium;
}

void SceneBuilder::assignMedia(const ShapeEntity& e, Shape& shape) {
    // A subsurface shape bounds its material's medium; outside is the current medium, as for
    // any shape without a transition (pbrt-v4's MediumInterface outside).
    if (const Medium* interior = subsurfaceMedium(shape.material)) {
        if (e.media.transition() && !e.media.inside.empty())
            warning(e.loc, "the shape's \"subsurface\" material fills it with its own medium; MediumInterface's inside " +
                               quoteForMessage(e.media.inside) + " is not used");
        shape.mediumInside = interior;
        shape.mediumOutside = mediumNamed(e.media.outside, e.media.loc);
        shape.mediumTransition = true;
        return;
    }
    if (!e.media.transition()) return;
    shape.mediumInside = mediumNamed(e.media.inside, e.media.loc);
    shape.mediumOutside = mediumNamed(e.media.outside, e.media.loc);
    shape.mediumTransition = true;
}

unsigned SceneBuilder::attach(RTCScene target, const Shape& shape) {
    RTCGeometry g = shape.buildGeometry(scene_.device_);
    unsigned id = rtcAttachGeometry(target, g);
    rtcReleaseGeometry(g);
    return id;
}

void SceneBuilder::addWorldShapes() {
    for (const ShapeEntity& e : desc_.shapes) {
        if (!(e.worldFromObject == e.worldFromObjectEnd)) {
            addMovingShape(e);
            continue;
        }
        std::unique_ptr<Shape> shape = createShape(e, e.worldFromObject, desc_.baseDirectory, textures_);
        if (!shape || shape->primitiveCount() == 0) continue;
        shape->material = materialFor(e);
        assignMedia(e, *shape);
        addAreaLights(e, *shape);
        if (skipped(*shape)) continue;
        unsigned id = attach(scene_.scene_, *shape);
        if (scene_.worldGeometry_.size() <= id) {
            scene_.worldGeometry_.resize(id + 1, nullptr);
            scene_.instanceOfGeometry_.resize(id + 1, -1);
        }
        scene_.worldGeometry_[id] = shape.get();
        scene_.shapes_.push_back(std::move(shape));
    }
}

int SceneBuilder::buildPrototype(const InstanceDefinition& def, const Transform& prototypeFromInstance) {
    RTCScene proto = rtcNewScene(scene_.device_);
    // The Scene owns (and releases) it from here: a bad shape below must not leak it.
    scene_.prototypeScenes_.push_back(proto);
    scene_.prototypeGeometry_.emplace_back();
    const int index = int(scene_.prototypeScenes_.size()) - 1;
    rtcSetSceneBuildQuality(proto, RTC_BUILD_QUALITY_HIGH);
    rtcSetSceneFlags(proto, kSceneFlags);
    for (const ShapeEntity& e : def.shapes) {
        // Embree here instances one level deep: a moving shape cannot be an instance inside one.
        if (!(e.worldFromObject == e.worldFromObjectEnd))
            warning(e.loc, "a moving shape inside ObjectBegin is not supported; its start transform is used");
        std::unique_ptr<Shape> shape = createShape(e, prototypeFromInstance * e.worldFromObject, desc_.baseDirectory, textures_);
        if (!shape || shape->primitiveCount() == 0) continue;
        shape->material = materialFor(e);
        assignMedia(e, *shape);
        if (skipped(*shape)) continue;
        unsigned id = attach(proto, *shape);
        std::vector<const Shape*>& geoms = scene_.prototypeGeometry_[size_t(index)];
        if (geoms.size() <= id) geoms.resize(id + 1, nullptr);
        geoms[id] = shape.get();
        scene_.shapes_.push_back(std::move(shape));
    }
    rtcCommitScene(proto);
    return index;
}

void SceneBuilder::addMovingShape(const ShapeEntity& e) {
    AnimatedTransform motion = motionOf(e.worldFromObject, e.worldFromObjectEnd);
    EmbreeMotion em = embreeMotion(motion);
    if (!em.exact) warning(e.loc, "the shape's scale changes along skewed axes; its motion is approximate");
    InstanceDefinition single;
    single.shapes.push_back(e);
    single.shapes.back().worldFromObject = single.shapes.back().worldFromObjectEnd = Transform();
    int proto = buildPrototype(single, em.prototypeFromObject);
    if (scene_.prototypeGeometry_[size_t(proto)].empty()) return;
    addInstance(proto, e.worldFromObject, motion, &em);
}

void SceneBuilder::addInstance(int proto, const Transform& worldFromPrototype, const AnimatedTransform& motion,
                               const EmbreeMotion* em) {
    RTCGeometry g = rtcNewGeometry(scene_.device_, RTC_GEOMETRY_TYPE_INSTANCE);
    rtcSetGeometryInstancedScene(g, scene_.prototypeScenes_[size_t(proto)]);
    Scene::Instance inst{worldFromPrototype, proto, {}, {}};
    if (motion.isAnimated() && em) {
        // Embree's time 0..1 spans TransformTimes (Scene::embreeTime maps the rays' times).
        rtcSetGeometryTimeStepCount(g, 2);
        for (unsigned k = 0; k < 2; ++k) rtcSetGeometryTransformQuaternion(g, k, &em->steps[k]);
        inst.motion = motion;
        inst.objectFromPrototype = em->prototypeFromObject.inverse();
        scene_.geometryMoves_ = true;
    } else {
        float xfm[12];
        const Matrix4& m = worldFromPrototype.matrix();
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 4; ++c) xfm[r * 4 + c] = m.m[r][c];
        rtcSetGeometryTransform(g, 0, RTC_FORMAT_FLOAT3X4_ROW_MAJOR, xfm);
    }
    rtcCommitGeometry(g);
    unsigned id = rtcAttachGeometry(scene_.scene_, g);
    rtcReleaseGeometry(g);
    if (scene_.worldGeometry_.size() <= id) {
        scene_.worldGeometry_.resize(id + 1, nullptr);
        scene_.instanceOfGeometry_.resize(id + 1, -1);
    }
    scene_.instanceOfGeometry_[id] = int(scene_.instances_.size());
    scene_.instances_.push_back(std::move(inst));
}

void SceneBuilder::addInstances() {
    std::map<std::string, int> prototypeIndex;
    for (const auto& [name, def] : desc_.instances) prototypeIndex[name] = buildPrototype(def, Transform());
    for (const InstanceUse& use : desc_.instanceUses) {
        auto it = prototypeIndex.find(use.name);
        if (it == prototypeIndex.end()) throw InputError(use.loc, "ObjectInstance " + quoteForMessage(use.name) + " is not defined");
        if (scene_.prototypeGeometry_[it->second].empty()) continue;
        AnimatedTransform motion = motionOf(use.worldFromInstance, use.worldFromInstanceEnd);
        if (!motion.isAnimated()) {
            addInstance(it->second, use.worldFromInstance, motion, nullptr);
            continue;
        }
        EmbreeMotion em = embreeMotion(motion);
        if (!em.exact) warning(use.loc, "the instance's scale changes along skewed axes; its motion is approximate");
        // A moving instance whose scale changes along rotated axes needs its geometry placed by
        // C: a prototype of its own.
        int proto = em.prototypeFromObject.isIdentity() ? it->second
                                                        : buildPrototype(desc_.instances.at(use.name), em.prototypeFromObject);
        addInstance(proto, use.worldFromInstance, motion, &em);
    }
}

void SceneBuilder::addLights() {
    for (const LightEntity& e : desc_.lights)
        if (auto light = createLight(e, desc_.baseDirectory)) {
            light->mediumInside = light->mediumOutside = mediumNamed(e.media.outside, e.media.loc);
            light->label = "LightSource \"" + e.type + "\" at " + e.loc.str();
            scene_.lights_.push_back(std::move(light));
        }
}

void SceneBuilder::build() {
    applyRenderOptions(desc_, scene_);
    scene_.device_ = rtcNewDevice(nullptr);
    if (!scene_.device_) throw std::runtime_error("cannot create the Embree device");
    rtcSetDeviceErrorFunction(scene_.device_, embreeError, nullptr);
    scene_.scene_ = rtcNewScene(scene_.device_);
    rtcSetSceneBuildQuality(scene_.scene_, RTC_BUILD_QUALITY_HIGH);
    rtcSetSceneFlags(scene_.scene_, kSceneFlags);

    createMaterials();
    createMedia();
    addWorldShapes();
    addInstances();
    addLights();
    scene_.motionStart_ = desc_.transformStartTime;
    scene_.motionEnd_ = desc_.transformEndTime;
    rtcCommitScene(scene_.scene_);
    {
        std::lock_guard<std::mutex> lock(gEmbreeErrorMutex);
        if (!gEmbreeError.empty()) {
            std::string msg = gEmbreeError;
            gEmbreeError.clear();
            throw std::runtime_error("Embree: " + msg);
        }
    }

    warnIfCameraMediumContradicted();

    RTCBounds b;
    rtcGetSceneBounds(scene_.scene_, &b);
    Vec3 lo(b.lower_x, b.lower_y, b.lower_z), hi(b.upper_x, b.upper_y, b.upper_z);
    if (isFinite(lo) && isFinite(hi) && lo.x <= hi.x) {
        scene_.center_ = (lo + hi) * 0.5f;
        scene_.radius_ = std::max(1e-3f, length(hi - lo) * 0.5f);
    }
    std::vector<float> power;
    for (size_t i = 0; i < scene_.lights_.size(); ++i) {
        Light& l = *scene_.lights_[i];
        l.index = int(i);
        l.preprocess(scene_.center_, scene_.radius_);
        if (l.type() == LightType::Infinite) scene_.infiniteLights_.push_back(&l);
        power.push_back(l.phi().luminance());
    }
    std::vector<const Light*> lights;
    for (const auto& l : scene_.lights_) lights.push_back(l.get());
    scene_.lightSampler_ = createLightSampler(scene_.settings().lightSampler, lights);
    // Light subpaths' choice: with a light tree of more than one leaf, mostly by what each light
    // sends to the camera (lights/emission_choice.h); otherwise by power.
    const auto* tree = dynamic_cast<const BVHLightSampler*>(scene_.lightSampler_.get());
    const LightSampler* towardsCamera = tree && tree->nodeCount() > 1 ? tree : nullptr;
    scene_.lightDistribution_ =
        AliasTable(emissionChoiceWeights(lights, power, towardsCamera, scene_.camera().position()));
}

std::unique_ptr<Scene> buildScene(const SceneDescription& desc, bool spectral) {
    auto scene = std::make_unique<Scene>();
    scene->settings().spectral = spectral;
    SceneBuilder(desc, *scene).build();
    return scene;
}

}  // namespace ps
