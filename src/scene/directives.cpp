#include "scene/directives.h"
#include "scene/color_space.h"

#include <algorithm>
#include <cctype>

#include "util/path.h"

namespace ps {

namespace {

// Values that Attribute defaults may copy into statements over a whole parse: a long
// default list applied to many shapes would otherwise grow memory quadratically.
constexpr size_t kAttributeValueBudget = size_t(1) << 28;

const char* kUpgradeHint = "; convert the file with `pbrt --upgrade`";

bool isV3MaterialName(const std::string& t) {
    static const char* const v3[] = {"matte", "plastic", "glass", "uber", "metal", "mirror", "substrate", "translucent"};
    return std::any_of(std::begin(v3), std::end(v3), [&](const char* n) { return t == n; });
}

std::string quote(const std::string& s) { return quoteForMessage(s); }

// pbrt-v4 matches option names case-insensitively, ignoring '-' and '_'.
std::string normalizeOptionName(const std::string& s) {
    std::string out;
    for (unsigned char c : s)
        if (c != '-' && c != '_') out += char(std::tolower(c));
    return out;
}

}  // namespace

DescriptionBuilder::DescriptionBuilder(SceneDescription& desc) : desc_(desc), attributeBudget_(kAttributeValueBudget) {
    // pbrt-v4's defaults (§7) and its default material, diffuse 0.5 (§5).
    desc_.camera.type = "perspective";
    desc_.film.type = "rgb";
    desc_.sampler.type = "zsobol";
    desc_.integrator.type = "volpath";
    desc_.filter.type = "gaussian";
    for (SceneEntity* e : {static_cast<SceneEntity*>(&desc_.camera), &desc_.film, &desc_.sampler, &desc_.integrator, &desc_.filter})
        e->params.baseDirectory = desc_.baseDirectory;
    MaterialEntity def;
    def.type = "diffuse";
    def.loc = SourceLoc{"<default material>", 0, 0};
    def.params.baseDirectory = desc_.baseDirectory;
    desc_.materials.push_back(std::move(def));
}

void DescriptionBuilder::fail(const Token& d, const std::string& msg) const {
    throw InputError(d.loc(), std::string(d.text) + ": " + msg);
}

// Where directives may appear (§8 Blocks; pbrt's VERIFY_OPTIONS / VERIFY_WORLD).
void DescriptionBuilder::requireOptions(const Token& d) const {
    if (inWorld_) fail(d, "not allowed after WorldBegin (it belongs in the options block before it)");
}
void DescriptionBuilder::requireWorld(const Token& d) const {
    if (!inWorld_) fail(d, "not allowed before WorldBegin (it belongs in the world block)");
}

// ---- transforms: the CTM is post-multiplied (§1) ----

void DescriptionBuilder::concat(const Token& d, const Transform& t) { setCtm(d, t, false); }

// pbrt-v4 accepts a singular or non-finite transform (its inverse becomes NaN); only
// placing a shape, light, camera or instance under it is an error (requireInvertibleCtm),
// which then names the directive that made it so.
void DescriptionBuilder::setCtm(const Token& d, const Transform& t, bool replaces) {
    for (Transform* key : {gs_.startTransformActive ? &gs_.ctm : nullptr, gs_.endTransformActive ? &gs_.ctmEnd : nullptr}) {
        if (!key) continue;
        Transform next = replaces ? t : *key * t;
        if (!next.isInvertible() && (replaces || key->isInvertible()))
            gs_.singularSince = std::string(d.text) + " at " + d.loc().str();
        *key = next;
    }
}

void DescriptionBuilder::requireInvertibleCtm(const Token& d) const {
    if (!gs_.ctm.isInvertible() || !gs_.ctmEnd.isInvertible())
        fail(d, "the current transform is singular or not finite (since " + gs_.singularSince + "), so nothing can be placed under it");
}

void DescriptionBuilder::identity(const Token& d) { setCtm(d, Transform(), true); }

void DescriptionBuilder::translate(const Token& d, Vec3 delta) { concat(d, Transform::translate(delta)); }

void DescriptionBuilder::scale(const Token& d, Vec3 s) { concat(d, Transform::scale(s)); }  // 0: singular

void DescriptionBuilder::rotate(const Token& d, float degrees, Vec3 axis) {
    concat(d, Transform::rotate(degrees, axis));  // a zero axis gives NaN, as pbrt-v4's Normalize
}

void DescriptionBuilder::lookAt(const Token& d, Vec3 eye, Vec3 target, Vec3 up) {
    auto worldFromCamera = Transform::lookAt(eye, target, up);
    if (!worldFromCamera) fail(d, "eye equals the look-at point, or the up vector is zero or parallel to the view direction");
    concat(d, worldFromCamera->inverse());  // LookAt post-multiplies camera-from-world
}

// The file lists the matrix column by column (numbers 13-15 are the translation), so the
// 16 numbers are transposed into our row-major Matrix4.
static Transform fromFileOrder(const double v[16]) {
    Matrix4 m;
    for (int col = 0; col < 4; ++col)
        for (int row = 0; row < 4; ++row) m.m[row][col] = float(v[col * 4 + row]);
    return Transform::fromMatrixOrSingular(m);
}

void DescriptionBuilder::transform(const Token& d, const double m[16]) { setCtm(d, fromFileOrder(m), true); }

void DescriptionBuilder::concatTransform(const Token& d, const double m[16]) { concat(d, fromFileOrder(m)); }

// Named coordinate systems keep both keyframes; CoordSysTransform restores both, whatever
// ActiveTransform selects (pbrt-v4's semantics).
void DescriptionBuilder::coordinateSystem(const Token&, const std::string& name) {
    namedCoordSys_[name] = {gs_.ctm, gs_.ctmEnd};
}

void DescriptionBuilder::coordSysTransform(const Token& d, const std::string& name) {
    auto it = namedCoordSys_.find(name);
    if (it == namedCoordSys_.end()) {
        warning(d.loc(), "CoordSysTransform: unknown coordinate system " + quote(name) + "; ignored");
        return;
    }
    gs_.ctm = it->second.first;
    gs_.ctmEnd = it->second.second;
    if (!gs_.ctm.isInvertible() || !gs_.ctmEnd.isInvertible()) gs_.singularSince = std::string(d.text) + " at " + d.loc().str();
}

void DescriptionBuilder::activeTransform(const Token&, const std::string& which) {
    gs_.startTransformActive = which != "EndTime";
    gs_.endTransformActive = which != "StartTime";
}

void DescriptionBuilder::transformTimes(const Token& d, float start, float end) {
    requireOptions(d);
    desc_.transformStartTime = start;
    desc_.transformEndTime = end;
}

// ---- options block ----

void DescriptionBuilder::setOptionEntity(SceneEntity& e, const Token& d, const std::string& type, ParamSet ps) {
    requireOptions(d);
    e.type = type;
    e.params = std::move(ps);
    e.loc = d.loc();
}

void DescriptionBuilder::camera(const Token& d, const std::string& type, ParamSet ps) {
    requireInvertibleCtm(d);
    setOptionEntity(desc_.camera, d, type, std::move(ps));
    // The CTM here is camera-from-world (§1).
    desc_.camera.worldFromCamera = gs_.ctm.inverse();
    desc_.camera.worldFromCameraEnd = gs_.ctmEnd.inverse();
    desc_.camera.transformStartTime = desc_.transformStartTime;
    desc_.camera.transformEndTime = desc_.transformEndTime;
    desc_.cameraGiven = true;
    desc_.camera.medium = gs_.media.outside;  // pbrt-v4's CameraMedium
    desc_.camera.mediumLoc = gs_.media.loc;
    namedCoordSys_["camera"] = {desc_.camera.worldFromCamera, desc_.camera.worldFromCameraEnd};
}

void DescriptionBuilder::film(const Token& d, const std::string& type, ParamSet ps) {
    if (type == "image") fail(d, "type \"image\" is pbrt-v3 syntax (pbrt-v4 calls it \"rgb\")" + std::string(kUpgradeHint));
    setOptionEntity(desc_.film, d, type, std::move(ps));
}

void DescriptionBuilder::sampler(const Token& d, const std::string& type, ParamSet ps) {
    setOptionEntity(desc_.sampler, d, type, std::move(ps));
}

void DescriptionBuilder::integrator(const Token& d, const std::string& type, ParamSet ps) {
    setOptionEntity(desc_.integrator, d, type, std::move(ps));
}

void DescriptionBuilder::pixelFilter(const Token& d, const std::string& type, ParamSet ps) {
    setOptionEntity(desc_.filter, d, type, std::move(ps));
}

void DescriptionBuilder::accelerator(const Token& d, const std::string&, ParamSet) {
    requireOptions(d);  // the renderer has its own acceleration structure: ignored silently
}

void DescriptionBuilder::worldBegin(const Token& d) {
    requireOptions(d);
    inWorld_ = true;
    gs_.ctm = gs_.ctmEnd = Transform();
    gs_.startTransformActive = gs_.endTransformActive = true;
    namedCoordSys_["world"] = {gs_.ctm, gs_.ctmEnd};
}

// ---- anywhere ----

void DescriptionBuilder::colorSpace(const Token& d, const std::string& name) {
    // pbrt-v4 reports an unknown space and keeps the current one.
    if (const RGBColorSpace* s = namedColorSpace(name))
        gs_.colorSpace = s;
    else
        warning(d.loc(), "ColorSpace " + quote(name) +
                             " is unknown (srgb, rec2020, dci-p3, aces2065-1); the current colour space stays");
}

void DescriptionBuilder::option(const Token& d, const std::string& name, const Token& value) {
    if (name.find_first_of(" \t") != std::string::npos)
        fail(d, "takes a bare name and value, as in Option \"seed\" 5; the typed form " + quote(name) + " is not accepted");
    const std::string n = normalizeOptionName(name);
    const std::string raw(value.text);
    auto bad = [&](const std::string& what) { fail(d, quote(name) + ": expected " + what + ", got " + raw); };
    static const char* const boolOptions[] = {"disablepixeljitter", "disabletexturefiltering", "disablewavelengthjitter",
                                              "forcediffuse",       "pixelstats",              "wavefront"};
    if (std::any_of(std::begin(boolOptions), std::end(boolOptions), [&](const char* o) { return n == o; })) {
        if (raw != "true" && raw != "false") bad("bare true or false");
    } else if (n == "displacementedgescale" || n == "seed") {
        if (value.isString() || value.is("[") || value.is("]")) bad("a number");
    } else if (n == "msereferenceimage" || n == "msereferenceout" || n == "rendercoordsys") {
        if (!value.isString()) bad("a quoted string");
        std::string s = Tokenizer::dequote(value);
        if (n == "rendercoordsys" && s != "camera" && s != "cameraworld" && s != "world")
            bad("\"camera\", \"cameraworld\" or \"world\"");
    } else {
        fail(d, "unknown option " + quote(name));
    }
    desc_.options[n] = value.isString() ? Tokenizer::dequote(value) : raw;
}

void DescriptionBuilder::attribute(const Token& d, const std::string& target, ParamSet ps) {
    auto t = attributeTarget(target);
    if (!t) fail(d, "unknown target " + quote(target) + " (expected \"shape\", \"light\", \"material\", \"medium\" or \"texture\")");
    gs_.addAttributes(*t, std::move(ps.params));
}

// Allowed anywhere, as in pbrt-v4 (a camera's medium is made before WorldBegin). The class
// is the "string type" parameter; the medium keeps the CTM here (grids are placed by it).
void DescriptionBuilder::makeNamedMedium(const Token& d, const std::string& name, ParamSet ps) {
    applyAttributes(AttributeTarget::Medium, ps, d);
    if (desc_.media.count(name)) fail(d, "medium " + quote(name) + " is already defined (at " + desc_.media[name].loc.str() + ")");
    const std::string type = ps.getString("type", "");
    if (type.empty()) fail(d, "medium " + quote(name) + " needs a \"string type\" parameter");
    requireInvertibleCtm(d);
    MediumEntity e;
    e.name = name;
    e.type = type;
    e.params = std::move(ps);
    e.loc = d.loc();
    e.worldFromMedium = gs_.ctm;
    desc_.media[name] = std::move(e);
}

// Names are resolved once the whole file is read (render/scene_builder.cpp): a medium may be
// defined after the MediumInterface that names it, as pbrt-v4 creates media after parsing.
void DescriptionBuilder::mediumInterface(const Token& d, const std::string& inside, const std::string& outside) {
    gs_.media = MediumNames{inside, outside, d.loc()};
}

// ---- world block ----

void DescriptionBuilder::attributeBegin(const Token& d) {
    requireWorld(d);
    if (d.is("TransformBegin") && !warnedTransformBegin_) {
        warnedTransformBegin_ = true;
        warning(d.loc(), "TransformBegin/TransformEnd are deprecated; treated as AttributeBegin/AttributeEnd");
    }
    pushed_.push_back(Pushed{gs_, false, d.loc()});
}

void DescriptionBuilder::attributeEnd(const Token& d) {
    requireWorld(d);
    if (pushed_.empty()) {  // pbrt reports this and carries on
        warning(d.loc(), std::string(d.text) + " without a matching AttributeBegin; ignored");
        return;
    }
    if (pushed_.back().object) fail(d, "mismatched nesting: ObjectBegin at " + pushed_.back().loc.str() + " is still open");
    gs_ = std::move(pushed_.back().state);
    pushed_.pop_back();
}

void DescriptionBuilder::reverseOrientation(const Token& d) {
    requireWorld(d);
    gs_.reverseOrientation = !gs_.reverseOrientation;
}

void DescriptionBuilder::applyAttributes(AttributeTarget target, ParamSet& ps, const Token& d) {
    size_t copied = gs_.applyAttributes(target, ps);
    if (copied > attributeBudget_) fail(d, "Attribute defaults copied into too many statements (resource limit)");
    attributeBudget_ -= copied;
}

void DescriptionBuilder::checkV3Material(const Token& d, const std::string& type, const ParamSet& ps) const {
    if (isV3MaterialName(type)) fail(d, "material " + quote(type) + " is pbrt-v3 syntax" + kUpgradeHint);
    if (const Param* p = ps.find("index"); p && !p->fromAttribute)
        throw InputError(p->loc, "parameter \"" + p->typeName + " index\" is pbrt-v3 syntax (pbrt-v4 calls it \"eta\")" + kUpgradeHint);
}

void DescriptionBuilder::material(const Token& d, const std::string& type, ParamSet ps) {
    requireWorld(d);
    applyAttributes(AttributeTarget::Material, ps, d);
    checkV3Material(d, type, ps);
    MaterialEntity m;
    m.type = type;
    m.params = std::move(ps);
    m.loc = d.loc();
    desc_.materials.push_back(std::move(m));
    gs_.material = MaterialRef{int(desc_.materials.size()) - 1, ""};
}

void DescriptionBuilder::makeNamedMaterial(const Token& d, const std::string& name, ParamSet ps) {
    requireWorld(d);
    applyAttributes(AttributeTarget::Material, ps, d);
    const Param* type = ps.find("type");
    if (!type || type->type != ParamType::String || type->strings.size() != 1 || type->strings[0].empty())
        fail(d, "named material " + quote(name) + " needs a \"string type\" parameter");
    MaterialEntity m;
    m.type = type->strings[0];
    checkV3Material(d, m.type, ps);
    if (desc_.namedMaterials.count(name)) fail(d, "named material " + quote(name) + " is defined twice");
    // The type is the entity's class, not a parameter of it.
    ps.params.erase(std::remove_if(ps.params.begin(), ps.params.end(), [](const Param& p) { return p.name == "type"; }),
                    ps.params.end());
    m.name = name;
    m.params = std::move(ps);
    m.loc = d.loc();
    desc_.namedMaterials.emplace(name, std::move(m));
}

void DescriptionBuilder::namedMaterial(const Token& d, const std::string& name) {
    requireWorld(d);
    gs_.material = MaterialRef{-1, name};  // resolved after parsing: it may be defined later (§8)
}

void DescriptionBuilder::texture(const Token& d, const std::string& name, const std::string& kind, const std::string& cls,
                                 ParamSet ps) {
    requireWorld(d);
    if (kind == "color") fail(d, "texture type \"color\" is pbrt-v3 syntax (pbrt-v4 uses \"spectrum\")" + std::string(kUpgradeHint));
    if (kind != "float" && kind != "spectrum") fail(d, "texture type must be \"float\" or \"spectrum\", not " + quote(kind));
    const bool isFloat = kind == "float";
    if (!(isFloat ? floatTextureNames_ : spectrumTextureNames_).insert(name).second)
        fail(d, kind + " texture " + quote(name) + " is defined twice");
    applyAttributes(AttributeTarget::Texture, ps, d);
    TextureEntity e;
    e.name = name;
    e.isFloat = isFloat;
    e.type = cls;
    e.params = std::move(ps);
    e.loc = d.loc();
    if (!(gs_.ctm == gs_.ctmEnd)) warning(d.loc(), "Texture: a moving texture space is not supported (as in pbrt-v4); the start transform is used");
    e.worldFromTexture = gs_.ctm;
    (isFloat ? desc_.floatTextures : desc_.spectrumTextures).push_back(std::move(e));
}

void DescriptionBuilder::lightSource(const Token& d, const std::string& type, ParamSet ps) {
    requireWorld(d);
    requireInvertibleCtm(d);
    applyAttributes(AttributeTarget::Light, ps, d);
    LightEntity e;
    e.type = type;
    e.params = std::move(ps);
    e.loc = d.loc();
    if (!(gs_.ctm == gs_.ctmEnd)) warning(d.loc(), "LightSource: moving lights are not supported (as in pbrt-v4); the start transform is used");
    e.worldFromLight = gs_.ctm;  // from/to are in this space (§3)
    e.media = gs_.media;
    desc_.lights.push_back(std::move(e));
}

void DescriptionBuilder::areaLightSource(const Token& d, const std::string& type, ParamSet ps) {
    requireWorld(d);
    applyAttributes(AttributeTarget::Light, ps, d);
    SceneEntity e;
    e.type = type;
    e.params = std::move(ps);
    e.loc = d.loc();
    desc_.areaLights.push_back(std::move(e));
    gs_.areaLight = int(desc_.areaLights.size()) - 1;  // applies to the following shapes in scope
}

void DescriptionBuilder::shape(const Token& d, const std::string& type, ParamSet ps) {
    requireWorld(d);
    requireInvertibleCtm(d);
    applyAttributes(AttributeTarget::Shape, ps, d);
    ShapeEntity e;
    e.type = type;
    e.params = std::move(ps);
    e.loc = d.loc();
    e.worldFromObject = gs_.ctm;
    e.worldFromObjectEnd = gs_.ctmEnd;
    if (gs_.areaLight >= 0 && !(gs_.ctm == gs_.ctmEnd)) fail(d, "moving area lights are not supported (as in pbrt-v4)");
    e.reverseOrientation = gs_.reverseOrientation;
    e.material = gs_.material;
    e.areaLight = gs_.areaLight;
    e.media = gs_.media;
    if (instance_) {
        if (e.areaLight >= 0) {
            warning(d.loc(), "area lights inside ObjectBegin are not supported (as in pbrt-v4); the shape does not emit");
            e.areaLight = -1;
        }
        instance_->shapes.push_back(std::move(e));
    } else {
        desc_.shapes.push_back(std::move(e));
    }
}

// ObjectBegin acts like AttributeBegin; the CTM inside the definition is baked into its
// shapes, and ObjectInstance's CTM applies on top (§8 Instancing).
void DescriptionBuilder::objectBegin(const Token& d, const std::string& name) {
    requireWorld(d);
    if (instance_) fail(d, "cannot be nested: ObjectBegin " + quote(instance_->name) + " is still open");
    if (desc_.instances.count(name)) fail(d, "object " + quote(name) + " is defined twice");
    pushed_.push_back(Pushed{gs_, true, d.loc()});
    InstanceDefinition& def = desc_.instances[name];
    def.name = name;
    def.loc = d.loc();
    instance_ = &def;
    instanceFromOuterFile_ = false;
}

void DescriptionBuilder::objectEnd(const Token& d) {
    requireWorld(d);
    if (!instance_) fail(d, "without a matching ObjectBegin");
    if (instanceFromOuterFile_) fail(d, "closes ObjectBegin " + quote(instance_->name) + " from outside the imported file");
    if (!pushed_.back().object) fail(d, "mismatched nesting: AttributeBegin at " + pushed_.back().loc.str() + " is still open");
    gs_ = std::move(pushed_.back().state);
    pushed_.pop_back();
    instance_ = nullptr;
}

void DescriptionBuilder::objectInstance(const Token& d, const std::string& name) {
    requireWorld(d);
    if (instance_) fail(d, "not allowed inside ObjectBegin " + quote(instance_->name));
    requireInvertibleCtm(d);
    desc_.instanceUses.push_back(InstanceUse{name, gs_.ctm, gs_.ctmEnd, d.loc()});
}

// ---- Import and the end ----

DescriptionBuilder::ImportScope DescriptionBuilder::beginImport(const Token& d) {
    requireWorld(d);
    ImportScope saved{gs_, std::move(pushed_), std::move(namedCoordSys_), instance_, instanceFromOuterFile_};
    // pbrt-v4 parses the file with a fresh builder holding a copy of the graphics state: no
    // open blocks and no named coordinate systems.
    pushed_.clear();
    namedCoordSys_.clear();
    if (instance_) instanceFromOuterFile_ = true;  // its shapes still join the open definition
    return saved;
}

void DescriptionBuilder::endImport(const Token& d, ImportScope&& saved) {
    if (!pushed_.empty())
        throw InputError(pushed_.back().loc, std::string(pushed_.back().object ? "ObjectBegin" : "AttributeBegin") +
                                                 ": no matching end in the file imported at " + d.loc().str());
    gs_ = std::move(saved.state);
    pushed_ = std::move(saved.pushed);
    namedCoordSys_ = std::move(saved.namedCoordSys);
    instance_ = saved.instance;
    instanceFromOuterFile_ = saved.instanceFromOuterFile;
}

void DescriptionBuilder::finish(const std::string& mainFile) {
    if (!inWorld_) throw InputError(SourceLoc{mainFile, 0, 0}, "the scene ends before WorldBegin");
    if (!pushed_.empty()) {
        const Pushed& p = pushed_.back();
        throw InputError(p.loc, p.object ? "ObjectBegin: no matching ObjectEnd" : "AttributeBegin: no matching AttributeEnd");
    }
    for (const InstanceUse& u : desc_.instanceUses)
        if (!desc_.instances.count(u.name)) throw InputError(u.loc, "ObjectInstance: object " + quote(u.name) + " is not defined");
}

}  // namespace ps
