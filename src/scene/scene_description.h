// The parsed scene: plain data straight from the file, before anything is built.
// The parser fills it; the renderer's scene builder turns it into geometry, lights and
// materials. Knows nothing of Embree.
#pragma once
#include <map>
#include <string>
#include <vector>
#include "math/transform.h"
#include "scene/params.h"

namespace ps {

struct SceneEntity {
    std::string type;  // class name: "perspective", "diffuse", "trianglemesh", ...
    ParamSet params;
    SourceLoc loc;
};

// The media a MediumInterface directive named (PBRT-CONVENTIONS §8: part of the graphics
// state), resolved against MakeNamedMedium after parsing as pbrt-v4 does; "" is vacuum.
struct MediumNames {
    std::string inside, outside;
    SourceLoc loc;  // the MediumInterface directive, for an undefined name's error
    bool transition() const { return inside != outside; }
};

struct MediumEntity : SceneEntity {
    std::string name;
    Transform worldFromMedium;  // the CTM at MakeNamedMedium (grid media's placement)
};

struct CameraEntity : SceneEntity {
    Transform worldFromCamera;     // inverse of the CTM at the Camera directive
    Transform worldFromCameraEnd;  // ... of its end keyframe (equal unless the camera moves)
    float transformStartTime = 0, transformEndTime = 1;  // TransformTimes at the Camera directive
    // pbrt-v4's CameraMedium: the outside medium current at the Camera directive.
    std::string medium;
    SourceLoc mediumLoc;
};

struct MaterialEntity : SceneEntity {
    std::string name;  // empty for anonymous `Material`
};

struct TextureEntity : SceneEntity {
    std::string name;
    bool isFloat = false;       // "float" or "spectrum"
    Transform worldFromTexture;
};

struct LightEntity : SceneEntity {
    Transform worldFromLight;
    MediumNames media;  // the MediumInterface current at LightSource (its outside is the light's)
};

// Which material a shape uses: an anonymous material by index, or a name resolved after
// parsing (pbrt-v4 allows NamedMaterial before MakeNamedMaterial).
struct MaterialRef {
    int index = -1;
    std::string name;
};

struct ShapeEntity : SceneEntity {
    Transform worldFromObject;     // the CTM's start keyframe
    Transform worldFromObjectEnd;  // its end keyframe: different for a moving shape
    bool reverseOrientation = false;
    MaterialRef material;
    int areaLight = -1;  // index into SceneDescription::areaLights, -1 when not emissive
    MediumNames media;   // only a transition (inside != outside) changes a crossing ray's medium
};

struct InstanceDefinition {
    std::string name;
    std::vector<ShapeEntity> shapes;  // transforms include the CTM inside ObjectBegin
    SourceLoc loc;
};

struct InstanceUse {
    std::string name;
    Transform worldFromInstance;
    Transform worldFromInstanceEnd;  // different for a moving instance
    SourceLoc loc;
};

struct SceneDescription {
    std::string sceneFile;      // the file named on the command line
    std::string baseDirectory;  // its directory: every relative path resolves here

    CameraEntity camera;        // type "perspective" by default
    SceneEntity film;           // "rgb"
    SceneEntity sampler;        // "zsobol"
    SceneEntity integrator;     // "volpath"
    SceneEntity filter;         // "gaussian"
    bool cameraGiven = false;
    // TransformTimes: the times of the CTM's two keyframes (0 and 1 by default).
    float transformStartTime = 0, transformEndTime = 1;

    std::vector<MaterialEntity> materials;                 // anonymous, by index
    std::map<std::string, MaterialEntity> namedMaterials;
    std::vector<TextureEntity> floatTextures, spectrumTextures;  // in definition order
    std::vector<ShapeEntity> shapes;
    std::vector<LightEntity> lights;
    std::vector<SceneEntity> areaLights;  // AreaLightSource entities referenced by shapes
    std::map<std::string, MediumEntity> media;  // MakeNamedMedium, by name
    std::map<std::string, InstanceDefinition> instances;
    std::vector<InstanceUse> instanceUses;
    std::map<std::string, std::string> options;  // Option "name" value, raw text
};

}  // namespace ps
