// pbrt-v4's "goniometric" light: a point light whose intensity over directions is a grey
// image in the equal-area octahedral layout of environment maps (math/equal_area.h),
// looked up at the nearest texel and multiplied by the spectrum I (in spectral mode at the
// path's wavelengths, normalised by its photometric integral as pbrt-v4 does). Its frame is
// the light's transform with y and z swapped (pbrt-v4's semantics), so the image's pole (+z,
// the image centre) points along the transform's +y. Emitted rays are importance-sampled by
// the image.
#pragma once
#include <vector>
#include "lights/light.h"
#include "lights/light_directions.h"
#include "mc/distribution.h"

namespace ps {

class GoniometricLight final : public Light {
public:
    // worldFromLight: the CTM of the LightSource (the y-z swap is applied here); values:
    // res x res intensities (row 0 at the top), negative values read as 0; I: the spectrum
    // times every scale.
    GoniometricLight(const Transform& worldFromLight, LightSpectrum I, std::vector<float> values, int res);
    std::optional<LightLiSample> sampleLi(const LightSampleContext& ctx, Vec2 u) const override;
    std::optional<LightLeSample> sampleLe(Vec2 uPos, Vec2 uDir, const SampledWavelengths* lambda) const override;
    void pdfLe(Vec3 p, Vec3 n, Vec3 w, float* pdfPos, float* pdfDir) const override;
    Spectrum L(Vec3, Vec3, Vec2, Vec3 w, const SampledWavelengths* lambda) const override { return intensity(w, lambda); }
    // 4 pi I times the image's mean (pbrt-v4's, exact for a rotation).
    Spectrum phi() const override;
    // The mean of the image's values (its intensity averaged over the sphere, in units of I).
    float meanValue() const;
    // At its position, emitting every way (4 pi times the mean intensity: its power).
    std::optional<LightBounds> bounds() const override;
    // Intensity towards unit world direction w leaving the light (at lambda; null: RGB).
    Spectrum intensity(Vec3 w, const SampledWavelengths* lambda = nullptr) const {
        return intensityLight(frame_.toLight(w), lambda);
    }

    // The y-z swap between the LightSource's frame and the image's.
    static Transform swapYZ();

private:
    Spectrum intensityLight(Vec3 wLight, const SampledWavelengths* lambda) const;

    LightDirections frame_;
    Vec3 pos_;
    LightSpectrum I_;
    std::vector<float> values_;
    int res_;
    Distribution2D distribution_;
};

}  // namespace ps
