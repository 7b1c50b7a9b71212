// Small scenes for the Metropolis tests (metropolis_test.cpp: pssmlt and mmlt;
// veach_mlt_test.cpp: mlt). Each carries an Integrator line that the tests override by name.
#pragma once
#include <cmath>
#include <string>

#include "app/furnace_scene.h"

namespace ps::test {

// The chain parameters of the tests: a bootstrap and chain count sized for small films. The
// image mean of an MLT render is b times a fixed total of splatted luminance, so its spread
// across seeds is mostly the bootstrap's estimate of b.
inline std::string mltIntegrator(int bootstrapSamples = 50000) {
    return R"(Integrator "pssmlt" "integer maxdepth" [ 5 ] "integer chains" [ 64 ] "integer bootstrapsamples" [ )" +
           std::to_string(bootstrapSamples) + " ]";
}

// The scene with another bootstrap sample count: b's error, common to the whole image, is
// most of an MLT image mean's spread, and mlt's bootstrap samples (one strategy of one
// path each) are cheaper and noisier than BDPT's.
inline std::string withBootstrap(std::string scene, int samples) {
    const std::string key = "\"integer bootstrapsamples\" [ ";
    const size_t at = scene.find(key) + key.size();
    return scene.replace(at, scene.find(' ', at) - at, std::to_string(samples));
}

// The scene with k times its Integrator line's chains.
inline std::string withChainsTimes(std::string scene, int k) {
    const std::string key = "\"integer chains\" [ ";
    const size_t at = scene.find(key) + key.size(), end = scene.find(' ', at);
    return scene.replace(at, end - at, std::to_string(k * std::stoi(scene.substr(at, end - at))));
}

// Where the agreement tests' chains are too few: a chain keeps the luck of its start (its
// wavelengths among it) a long while, so more chains, not longer ones, bring a block's sigma
// across renders down. On the mirror scene in spectral mode 2x the mutations took it from
// 1.40 to 1.30 of agreement.h's bound, 4x the chains at the same cost to 0.71. The tests
// that use it run this many times the chains, each as long (this many times the mutations).
constexpr int kMoreChains = 4;

// A sphere lit from inside by its own emission, albedo 0.6: every pixel sees Le sum_k 0.6^k
// (app/furnace_scene.h's scene, with the tests' Integrator line).
inline std::string furnace() {
    std::string text = kFurnace;
    return text.insert(text.find("WorldBegin"), mltIntegrator() + "\n");
}
inline const double kFurnaceExact = kFurnaceValue;

// A 1 x 1 x 1 box open towards the camera with coloured walls; `light` and `walls` set the
// emission and the side walls' reflectances.
inline std::string box(const std::string& light, const std::string& left, const std::string& right) {
    return std::string(R"(
        LookAt 0 0.5 2.2  0 0.5 0  0 1 0
        Camera "perspective" "float fov" [ 30 ]
        Film "rgb" "integer xresolution" [ 24 ] "integer yresolution" [ 24 ]
        PixelFilter "box"
        )") + mltIntegrator() + R"(
        WorldBegin
        AttributeBegin
          AreaLightSource "diffuse" "rgb L" [ )" + light + R"( ]
          Shape "bilinearmesh" "point3 P" [ -0.2 0.99 -0.2   0.2 0.99 -0.2   -0.2 0.99 0.2   0.2 0.99 0.2 ]
        AttributeEnd
        Material "diffuse" "rgb reflectance" [ 0.7 0.7 0.7 ]
        Shape "bilinearmesh" "point3 P" [ -0.5 0 0.5   0.5 0 0.5   -0.5 0 -0.5   0.5 0 -0.5 ]
        Shape "bilinearmesh" "point3 P" [ -0.5 1 -0.5   0.5 1 -0.5   -0.5 1 0.5   0.5 1 0.5 ]
        Shape "bilinearmesh" "point3 P" [ -0.5 0 -0.5   0.5 0 -0.5   -0.5 1 -0.5   0.5 1 -0.5 ]
        Material "diffuse" "rgb reflectance" [ )" + left + R"( ]
        Shape "bilinearmesh" "point3 P" [ -0.5 0 0.5   -0.5 0 -0.5   -0.5 1 0.5   -0.5 1 -0.5 ]
        Material "diffuse" "rgb reflectance" [ )" + right + R"( ]
        Shape "bilinearmesh" "point3 P" [ 0.5 0 -0.5   0.5 0 0.5   0.5 1 -0.5   0.5 1 0.5 ]
        Material "diffuse" "rgb reflectance" [ 0.5 0.5 0.8 ]
        Shape "sphere" "float radius" [ 0.2 ]
    )";
}

// A caustic: a small area light above a glass sphere focuses on a diffuse floor (L S S D E).
inline std::string glassCaustic() {
    return std::string(R"(
        LookAt 0 2.2 2.6  0 0.3 0  0 1 0
        Camera "perspective" "float fov" [ 30 ]
        Film "rgb" "integer xresolution" [ 24 ] "integer yresolution" [ 24 ]
        PixelFilter "box"
        )") + mltIntegrator(150000) + R"(
        WorldBegin
        AttributeBegin
          AreaLightSource "diffuse" "rgb L" [ 27 27 27 ]
          Shape "bilinearmesh" "point3 P" [ -0.15 2.5 -0.15   0.15 2.5 -0.15   -0.15 2.5 0.15   0.15 2.5 0.15 ]
        AttributeEnd
        Material "diffuse" "rgb reflectance" [ 0.8 0.8 0.8 ]
        Shape "bilinearmesh" "point3 P" [ -3 0 3   3 0 3   -3 0 -3   3 0 -3 ]
        AttributeBegin
          Material "dielectric" "float eta" [ 1.5 ]
          Translate 0 0.9 0
          Shape "sphere" "float radius" [ 0.5 ]
        AttributeEnd
    )";
}

// The caustic in colour and dispersed (spectral mode): a flint-glass sphere (glass-F11, or
// another spectrally varying `eta` parameter), an orange floor, a wider and dimmer light.
inline std::string dispersiveGlassCaustic(const std::string& eta = R"("spectrum eta" "glass-F11")") {
    std::string scene = glassCaustic();
    auto replace = [&](const std::string& from, const std::string& to) {
        const size_t at = scene.find(from);
        if (at != std::string::npos) scene.replace(at, from.size(), to);
    };
    replace(R"("float eta" [ 1.5 ])", eta);
    replace(R"("rgb reflectance" [ 0.8 0.8 0.8 ])", R"("rgb reflectance" [ 0.8 0.6 0.4 ])");
    replace(R"("rgb L" [ 27 27 27 ])", R"("rgb L" [ 6.75 6.75 6.75 ])");
    replace(R"([ -0.15 2.5 -0.15   0.15 2.5 -0.15   -0.15 2.5 0.15   0.15 2.5 0.15 ])",
            R"([ -0.3 2.5 -0.3   0.3 2.5 -0.3   -0.3 2.5 0.3   0.3 2.5 0.3 ])");
    return scene;
}

// An area light seen only in a smooth mirror, and a point light over the floor.
inline std::string lightSeenInAMirror() {
    return std::string(R"(
        LookAt 0 1 3  0 0.7 0  0 1 0
        Camera "perspective" "float fov" [ 35 ]
        Film "rgb" "integer xresolution" [ 24 ] "integer yresolution" [ 24 ]
        PixelFilter "box"
        )") + mltIntegrator(200000) + R"(
        WorldBegin
        LightSource "point" "rgb I" [ 2 2 2 ] "point3 from" [ 0.6 1.5 1 ]
        AttributeBegin
          AreaLightSource "diffuse" "rgb L" [ 6 6 6 ] "bool twosided" true
          Shape "bilinearmesh" "point3 P" [ -0.4 0.6 3.5   0.4 0.6 3.5   -0.4 1.4 3.5   0.4 1.4 3.5 ]
        AttributeEnd
        Material "diffuse" "rgb reflectance" [ 0.7 0.7 0.7 ]
        Shape "bilinearmesh" "point3 P" [ -2 0 4   2 0 4   -2 0 -1   2 0 -1 ]
        Material "conductor" "rgb reflectance" [ 0.9 0.9 0.9 ] "float roughness" [ 0 ]
        Shape "bilinearmesh" "point3 P" [ -1 0 -1   1 0 -1   -1 2 -1   1 2 -1 ]
    )";
}

// A spot light seen in a mirror patch on a diffuse wall through a thin lens (radius 0.25,
// focused at 4, nearer than the light's mirror image at 7.1): a bokeh disk of L S E paths,
// which only light walks whose ray crosses the lens sample (t = 0, thesis §10.2: a delta
// light, no join at the mirror), about 2.5 pixels wide inside the 4 x 4 block at pixels
// 4-7 (97% of the image), beside the wall that the cone's edge lights around the patch
// (L D E: every strategy). The spot aims at the mirror image of the lens.
inline std::string spotInAMirrorThroughALens() {
    return std::string(R"(
        LookAt 0 1 3  0 1 0  0 1 0
        Camera "perspective" "float fov" [ 35 ] "float lensradius" [ 0.25 ] "float focaldistance" [ 4 ]
        Film "rgb" "integer xresolution" [ 16 ] "integer yresolution" [ 16 ]
        PixelFilter "box"
        )") + mltIntegrator(20000) + R"(
        WorldBegin
        LightSource "spot" "rgb I" [ 4 4 4 ] "point3 from" [ 0.55 1.55 2 ] "point3 to" [ 0 1 -5 ]
          "float coneangle" [ 12 ] "float conedeltaangle" [ 6 ]
        Material "diffuse" "rgb reflectance" [ 0.7 0.7 0.7 ]
        Shape "bilinearmesh" "point3 P" [ -2 0 4   2 0 4   -2 0 -1   2 0 -1 ]
        Shape "bilinearmesh" "point3 P" [ -2 0 -1.001   2 0 -1.001   -2 2.5 -1.001   2 2.5 -1.001 ]
        Material "conductor" "rgb reflectance" [ 0.9 0.9 0.9 ] "float roughness" [ 0 ]
        Shape "bilinearmesh" "point3 P" [ 0.014 1.014 -1   0.614 1.014 -1   0.014 1.614 -1   0.614 1.614 -1 ]
    )";
}

// A point light of intensity pi at the centre of a closed diffuse sphere of radius 1 and
// albedo 0.5 (maxdepth 5): every pixel sees sum_{k=1..5} 0.5^k.
inline std::string pointLightInASphere() {
    return std::string(R"(
        LookAt 0 0 -0.2  0 0 1  0 1 0
        Camera "perspective" "float fov" [ 60 ]
        Film "rgb" "integer xresolution" [ 16 ] "integer yresolution" [ 16 ]
        PixelFilter "box"
        )") + mltIntegrator() + R"(
        WorldBegin
        LightSource "point" "rgb I" [ 3.14159265358979 3.14159265358979 3.14159265358979 ]
        Material "diffuse" "rgb reflectance" [ 0.5 0.5 0.5 ]
        Shape "sphere" "float radius" [ 1 ]
    )";
}

// The glass caustic (from a larger light, of the same power) seen through a thin glass pane
// between the camera and the floor: paths E S D S S L, whose D vertex joins neither
// neighbour (both specular): what the multi-chain perturbation moves. (BDPT reaches them
// only by camera walks that hit the light.)
inline std::string causticThroughGlass() {
    std::string scene = glassCaustic();
    auto replace = [&](const std::string& from, const std::string& to) { scene.replace(scene.find(from), from.size(), to); };
    replace("-0.15 2.5 -0.15   0.15 2.5 -0.15   -0.15 2.5 0.15   0.15 2.5 0.15", "-0.4 2.5 -0.4   0.4 2.5 -0.4   -0.4 2.5 0.4   0.4 2.5 0.4");
    replace("27 27 27", "3.8 3.8 3.8");
    scene += R"(
        AttributeBegin
          Material "thindielectric" "float eta" [ 1.5 ]
          Shape "bilinearmesh" "point3 P" [ -1.5 0.05 1.2   1.5 0.05 1.2   -1.5 1.6 1.2   1.5 1.6 1.2 ]
        AttributeEnd
    )";
    return scene;
}

// A door ajar (thesis §11.5's test scene, small): two closed diffuse rooms divided by a wall
// whose only opening is a narrow slit; the light, on the far room's ceiling, reaches the
// camera's room only through it, so every lit path squeezes through the slit.
inline std::string doorAjar() {
    return std::string(R"(
        LookAt 0 0.6 -1.9  0 0.4 0  0 1 0
        Camera "perspective" "float fov" [ 60 ]
        Film "rgb" "integer xresolution" [ 16 ] "integer yresolution" [ 16 ]
        PixelFilter "box"
        )") + mltIntegrator(200000) + R"(
        WorldBegin
        AttributeBegin
          AreaLightSource "diffuse" "rgb L" [ 12 12 12 ]
          Shape "bilinearmesh" "point3 P" [ -0.3 1.19 0.4   0.3 1.19 0.4   -0.3 1.19 0.8   0.3 1.19 0.8 ]
        AttributeEnd
        Material "diffuse" "rgb reflectance" [ 0.7 0.7 0.7 ]
        Shape "bilinearmesh" "point3 P" [ -1 0 1   1 0 1   -1 0 -2   1 0 -2 ]
        Shape "bilinearmesh" "point3 P" [ -1 1.2 -2   1 1.2 -2   -1 1.2 1   1 1.2 1 ]
        Shape "bilinearmesh" "point3 P" [ -1 0 -2   -1 0 1   -1 1.2 -2   -1 1.2 1 ]
        Shape "bilinearmesh" "point3 P" [ 1 0 1   1 0 -2   1 1.2 1   1 1.2 -2 ]
        Shape "bilinearmesh" "point3 P" [ -1 0 -2   1 0 -2   -1 1.2 -2   1 1.2 -2 ]
        Shape "bilinearmesh" "point3 P" [ -1 0 1   1 0 1   -1 1.2 1   1 1.2 1 ]
        Material "diffuse" "rgb reflectance" [ 0.6 0.5 0.4 ]
        Shape "bilinearmesh" "point3 P" [ -1 0 0   0.2 0 0   -1 1.2 0   0.2 1.2 0 ]
        Shape "bilinearmesh" "point3 P" [ 0.35 0 0   1 0 0   0.35 1.2 0   1 1.2 0 ]
        Shape "bilinearmesh" "point3 P" [ 0.2 1 0   0.35 1 0   0.2 1.2 0   0.35 1.2 0 ]
    )";
}

inline const double kPointLightInASphereExact = 0.5 + 0.25 + 0.125 + 0.0625 + 0.03125;

}  // namespace ps::test
