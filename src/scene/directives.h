// The meaning of each pbrt-v4 directive (PBRT-CONVENTIONS §1, §8): the parser hands over
// parsed arguments; this class keeps the graphics state and fills the SceneDescription.
// Every error names the directive's file:line:column and the directive itself.
#pragma once
#include <map>
#include <set>
#include <string>
#include <vector>
#include "scene/graphics_state.h"
#include "scene/scene_description.h"
#include "scene/tokenizer.h"

namespace ps {

class DescriptionBuilder {
public:
    explicit DescriptionBuilder(SceneDescription& desc);

    bool inWorld() const { return inWorld_; }

    // Transforms (allowed anywhere). `d` is the directive's token.
    void identity(const Token& d);
    void translate(const Token& d, Vec3 delta);
    void scale(const Token& d, Vec3 s);
    void rotate(const Token& d, float degrees, Vec3 axis);
    void lookAt(const Token& d, Vec3 eye, Vec3 target, Vec3 up);
    // The 16 numbers as they appear in the file (column by column).
    void transform(const Token& d, const double m[16]);
    void concatTransform(const Token& d, const double m[16]);
    void coordinateSystem(const Token& d, const std::string& name);
    void coordSysTransform(const Token& d, const std::string& name);
    void activeTransform(const Token& d, const std::string& which);
    void transformTimes(const Token& d, float start, float end);

    // Options block.
    void camera(const Token& d, const std::string& type, ParamSet ps);
    void film(const Token& d, const std::string& type, ParamSet ps);
    void sampler(const Token& d, const std::string& type, ParamSet ps);
    void integrator(const Token& d, const std::string& type, ParamSet ps);
    void pixelFilter(const Token& d, const std::string& type, ParamSet ps);
    void accelerator(const Token& d, const std::string& type, ParamSet ps);
    void worldBegin(const Token& d);

    // Anywhere.
    void colorSpace(const Token& d, const std::string& name);
    // The colour space of RGB values written here.
    const RGBColorSpace* currentColorSpace() const { return gs_.colorSpace; }
    void option(const Token& d, const std::string& name, const Token& value);
    void attribute(const Token& d, const std::string& target, ParamSet ps);
    void makeNamedMedium(const Token& d, const std::string& name, ParamSet ps);
    void mediumInterface(const Token& d, const std::string& inside, const std::string& outside);

    // World block.
    void attributeBegin(const Token& d);
    void attributeEnd(const Token& d);
    void reverseOrientation(const Token& d);
    void material(const Token& d, const std::string& type, ParamSet ps);
    void makeNamedMaterial(const Token& d, const std::string& name, ParamSet ps);
    void namedMaterial(const Token& d, const std::string& name);
    void texture(const Token& d, const std::string& name, const std::string& kind, const std::string& cls, ParamSet ps);
    void lightSource(const Token& d, const std::string& type, ParamSet ps);
    void areaLightSource(const Token& d, const std::string& type, ParamSet ps);
    void shape(const Token& d, const std::string& type, ParamSet ps);
    void objectBegin(const Token& d, const std::string& name);
    void objectEnd(const Token& d);
    void objectInstance(const Token& d, const std::string& name);

    // Import parses a file against a copy of the graphics state (§8): nothing but the
    // entities it defines survives it. beginImport saves and resets; endImport checks the
    // imported file closed its blocks and restores.
    struct ImportScope;
    ImportScope beginImport(const Token& d);
    void endImport(const Token& d, ImportScope&& saved);

    // End of the main file: unclosed blocks, missing WorldBegin, undefined instances.
    void finish(const std::string& mainFile);

private:
    struct Pushed {
        GraphicsState state;
        bool object = false;  // pushed by ObjectBegin rather than AttributeBegin
        SourceLoc loc;
    };

    [[noreturn]] void fail(const Token& d, const std::string& msg) const;
    void requireOptions(const Token& d) const;
    void requireWorld(const Token& d) const;
    void concat(const Token& d, const Transform& t);
    // Sets the active keyframes of the CTM to t (replaces) or to themselves times t.
    void setCtm(const Token& d, const Transform& t, bool replaces);
    void requireInvertibleCtm(const Token& d) const;
    void setOptionEntity(SceneEntity& e, const Token& d, const std::string& type, ParamSet ps);
    void applyAttributes(AttributeTarget target, ParamSet& ps, const Token& d);
    void checkV3Material(const Token& d, const std::string& type, const ParamSet& ps) const;

    SceneDescription& desc_;
    GraphicsState gs_;
    std::vector<Pushed> pushed_;
    std::map<std::string, std::pair<Transform, Transform>> namedCoordSys_;  // both keyframes
    std::set<std::string> floatTextureNames_, spectrumTextureNames_;
    bool inWorld_ = false;
    InstanceDefinition* instance_ = nullptr;  // the ObjectBegin being defined
    bool instanceFromOuterFile_ = false;      // ... opened outside the current Import
    size_t attributeBudget_;                  // values Attribute defaults may still copy
    bool warnedTransformBegin_ = false;
};

struct DescriptionBuilder::ImportScope {
    GraphicsState state;
    std::vector<Pushed> pushed;
    std::map<std::string, std::pair<Transform, Transform>> namedCoordSys;
    InstanceDefinition* instance = nullptr;
    bool instanceFromOuterFile = false;
};

}  // namespace ps
