// Typed parameter lists of pbrt-v4 directives ("float fov" [45] ...). Every lookup marks
// the parameter used, so parameters nobody asked for can be reported by name.
#pragma once
#include <optional>
#include <string>
#include <vector>
#include "math/spectrum.h"
#include "math/vec.h"
#include "spectral/spectrum_source.h"
#include "util/error.h"

namespace ps {

enum class ParamType { Float, Integer, Bool, String, Point2, Vector2, Point3, Vector3, Normal, RGB, Blackbody, Spectrum, Texture };

// How a spectrum-valued parameter is used; decides clamping and normalisation
// (PBRT-CONVENTIONS §3, §6): albedos are clamped to [0,1]; illuminant spectra given as
// `spectrum`/`blackbody` are normalised to luminance 1; RGB illuminants keep their magnitude.
enum class SpectrumKind { Albedo, Unbounded, Illuminant };

struct RGBColorSpace;

struct Param {
    ParamType type = ParamType::Float;
    std::string typeName, name;
    std::vector<double> numbers;       // float, integer, point*, vector*, normal, rgb, blackbody, numeric spectrum
    std::vector<std::string> strings;  // string, texture, named spectrum
    std::vector<bool> bools;
    SourceLoc loc;
    bool fromAttribute = false;  // supplied by an Attribute directive: never reported unused
    mutable bool used = false;
};

class ParamSet {
public:
    // A repeated name replaces the earlier value (last occurrence wins, as in pbrt-v4).
    void add(Param p);
    // Adds p only if no parameter of that name exists (Attribute defaults).
    void addDefault(Param p);

    bool has(const std::string& name) const { return find(name) != nullptr; }
    const Param* find(const std::string& name) const;

    // Single values: the default when absent; an InputError naming the location when the
    // parameter exists with the wrong type or the wrong number of values.
    float getFloat(const std::string& name, float def) const;
    int getInt(const std::string& name, int def) const;
    bool getBool(const std::string& name, bool def) const;
    std::string getString(const std::string& name, const std::string& def) const;
    Vec3 getPoint3(const std::string& name, Vec3 def) const;
    Vec3 getVector3(const std::string& name, Vec3 def) const;

    // Arrays: empty when absent.
    std::vector<float> getFloats(const std::string& name) const;
    std::vector<int> getInts(const std::string& name) const;
    std::vector<std::string> getStrings(const std::string& name) const;
    std::vector<Vec2> getPoint2s(const std::string& name) const;
    std::vector<Vec3> getPoint3s(const std::string& name) const;
    std::vector<Vec3> getNormals(const std::string& name) const;
    std::vector<Vec3> getVector3s(const std::string& name) const;

    // rgb / spectrum (inline pairs, named, or file) / blackbody, converted to RGB.
    std::optional<Spectrum> getSpectrum(const std::string& name, SpectrumKind kind) const;
    // The same parameter as the spectrum pbrt-v4 makes of it, for spectral rendering: rgb
    // lifted in the parameter's colour space (Albedo: RGBAlbedoSpectrum, Unbounded:
    // RGBUnboundedSpectrum, Illuminant: RGBIlluminantSpectrum), blackbody normalised to a peak
    // of 1, named spectra with their tables, inline and file spectra piecewise linear. Not
    // normalised as a light's emission (lights divide by SpectrumSource::photometric()).
    // Validated as getSpectrum does; nullopt when absent.
    std::optional<SpectrumSource> getSpectrumSource(const std::string& name, SpectrumKind kind) const;
    // Whether that rgb / spectrum / blackbody value changes with wavelength (rgb: unequal
    // components; spectrum: not one value over the visible range). False when absent.
    bool spectrallyVarying(const std::string& name) const;
    // Name of the texture bound by `"texture name" "texname"`, or "" when absent.
    std::string getTexture(const std::string& name) const;

    // Warn once for each parameter never looked up, naming it and where it was given.
    void reportUnused(const std::string& context) const;

    SourceLoc loc;               // the directive's location
    std::string baseDirectory;   // for resolving relative file names (spectrum files)
    // The ColorSpace in effect where the parameters were written (null: sRGB): their RGB
    // values are in it.
    const RGBColorSpace* colorSpace = nullptr;
    std::vector<Param> params;
    // Every name the scene's reader asked for (find): the names this directive knows, from
    // which reportUnused suggests the nearest to a misspelt one.
    mutable std::vector<std::string> asked;
};

}  // namespace ps
