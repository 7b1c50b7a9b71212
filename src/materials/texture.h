// Textures: functions of the surface point evaluated per shading point.
#pragma once
#include "math/spectrum.h"
#include "math/vec.h"

namespace ps {

struct SampledWavelengths;  // spectral/wavelengths.h

struct TextureEvalContext {
    Vec3 p;   // world-space position
    Vec3 n;   // geometric normal (pbrt-v4's textures see this one, not the shading normal)
    Vec2 uv;  // surface parameterisation
    // The path's wavelengths in spectral mode (null in RGB mode): spectrum textures return
    // their values at them. Not const: a material with a dispersive index keeps only the
    // first (SampledWavelengths::terminateSecondary), as pbrt-v4's GetBxDF does.
    SampledWavelengths* lambda = nullptr;
};

class FloatTexture {
public:
    virtual ~FloatTexture() = default;
    virtual float evaluate(const TextureEvalContext& ctx) const = 0;
};

class SpectrumTexture {
public:
    virtual ~SpectrumTexture() = default;
    virtual Spectrum evaluate(const TextureEvalContext& ctx) const = 0;
};

}  // namespace ps
