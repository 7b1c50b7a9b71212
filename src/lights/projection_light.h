// pbrt-v4's "projection" light: a point light that projects an RGB image through a
// perspective frustum, like a slide projector. In the light's frame (the LightSource's
// transform with y negated, pbrt-v4's semantics, so that the image's top row points along
// the transform's +y) it looks along +z; a direction w with w.z >= 1e-3 lands on the screen
// at (w.x, w.y) / (w.z tan(fov / 2)). The screen spans [-a, a] x [-1, 1] for an image aspect
// ratio a = width / height > 1, else [-1, 1] x [-1/a, 1/a] (fov spans the shorter axis);
// columns run along screen x, rows along screen y, and the intensity is the nearest
// texel's RGB (in spectral mode lifted at the path's wavelengths as an sRGB illuminant, as
// pbrt-v4 lifts it in the image's colour space); outside the screen it is zero. Emitted rays
// are importance-sampled by texel values times the solid angle each texel subtends.
#pragma once
#include "image/image.h"
#include "lights/light.h"
#include "lights/light_directions.h"
#include "mc/distribution.h"

namespace ps {

class ProjectionLight final : public Light {
public:
    // worldFromLight: the CTM of the LightSource (the y flip is applied here); image RGB
    // (negative values read as 0) times scale is the intensity.
    ProjectionLight(const Transform& worldFromLight, Image image, float scale, float fovDegrees);
    std::optional<LightLiSample> sampleLi(const LightSampleContext& ctx, Vec2 u) const override;
    std::optional<LightLeSample> sampleLe(Vec2 uPos, Vec2 uDir, const SampledWavelengths* lambda) const override;
    void pdfLe(Vec3 p, Vec3 n, Vec3 w, float* pdfPos, float* pdfDir) const override;
    Spectrum L(Vec3, Vec3, Vec2, Vec3 w, const SampledWavelengths* lambda) const override { return intensity(w, lambda); }
    // pbrt-v4's power: texel values times their solid angles at the texel centres.
    Spectrum phi() const override;
    // At its position, emitting within the cone that holds its frustum; it weighs in as 4 pi
    // times its mean intensity over the screen, as point-like lights do (delta_lights.cpp).
    std::optional<LightBounds> bounds() const override;
    Spectrum intensity(Vec3 w, const SampledWavelengths* lambda = nullptr) const {
        return intensityLight(frame_.toLight(w), lambda);
    }

    // The screen's geometry for an image of w x h texels and fov in degrees (shared with the
    // normalisation of "power", which needs it before the light exists).
    struct Screen {
        float x0, x1, y0, y1;  // bounds in screen units
        float tanHalfFov;
        // Area of the screen on the plane z = 1 of the light's frame.
        float planeArea() const { return (x1 - x0) * (y1 - y0) * tanHalfFov * tanHalfFov; }
        // cos^3 of the angle to +z of the direction through screen point (sx, sy): the solid
        // angle per unit area of the plane z = 1 there.
        float cos3(float sx, float sy) const;
        // cos3 at the centre of texel (x, y) of a w x h image.
        float texelCos3(int x, int y, int w, int h) const;
    };
    static Screen screenFor(int width, int height, float fovDegrees);

private:
    Spectrum intensityLight(Vec3 wLight, const SampledWavelengths* lambda) const;
    // Screen (u, v) in [0,1]^2 of light direction w, or false outside the frustum.
    bool screenUV(Vec3 wLight, Vec2* uv) const;

    LightDirections frame_;
    Vec3 pos_;
    Image image_;
    float scale_;
    Screen screen_;
    Distribution2D distribution_;
};

}  // namespace ps
