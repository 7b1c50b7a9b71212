#include "lights/infinite_lights.h"

#include "lights/infinity_disk.h"
#include "math/equal_area.h"
#include "math/warp.h"

namespace ps {

std::optional<LightLiSample> UniformInfiniteLight::sampleLi(const LightSampleContext& ctx, Vec2 u) const {
    Vec3 wi = sampleUniformSphere(u);
    return LightLiSample{L_(ctx.lambda), wi, uniformSpherePdf(), ctx.p + wi * (2 * sceneRadius_ + length(ctx.p - sceneCenter_)), {}};
}

float UniformInfiniteLight::pdfLi(const LightSampleContext&, Vec3, const SurfaceInteraction*) const {
    return uniformSpherePdf();
}

// Direction as in sampleLi, origin on the disk at infinity.
std::optional<LightLeSample> UniformInfiniteLight::sampleLe(Vec2 uPos, Vec2 uDir, const SampledWavelengths* lambda) const {
    Vec3 wl = sampleUniformSphere(uDir);
    return LightLeSample{L_(lambda), rayFromInfinityDisk(wl, sceneCenter_, sceneRadius_, uPos), {},
                         infinityDiskPdf(sceneRadius_), uniformSpherePdf(), {}};
}

void UniformInfiniteLight::pdfLe(Vec3, Vec3, Vec3, float* pdfPos, float* pdfDir) const {
    *pdfPos = infinityDiskPdf(sceneRadius_);
    *pdfDir = uniformSpherePdf();
}

ImageInfiniteLight::ImageInfiniteLight(Image image, float scale, const Transform& worldFromLight, Layout layout)
    : Light(LightType::Infinite), image_(std::move(image)), scale_(scale), worldFromLight_(worldFromLight),
      layout_(layout) {
    int w = image_.width, h = image_.height;
    std::vector<float> weights(size_t(w) * h);
    for (int y = 0; y < h; ++y) {
        // Latitude-longitude rows shrink towards the poles by sin(theta).
        float rowScale = layout_ == Layout::LatLong ? std::sin(kPi * (y + 0.5f) / h) : 1.0f;
        for (int x = 0; x < w; ++x) weights[size_t(y) * w + x] = image_.get(x, y).luminance() * rowScale;
    }
    distribution_ = Distribution2D(weights, w, h);
}

Vec2 ImageInfiniteLight::directionToUV(Vec3 w) const {
    if (layout_ == Layout::EqualArea) return equalAreaSphereToSquare(w);
    // z up: theta from +z along rows, phi around z along columns.
    float theta = safeAcos(w.z);
    float phi = std::atan2(w.y, w.x);
    if (phi < 0) phi += 2 * kPi;
    return {phi * kInv2Pi, theta * kInvPi};
}

Vec3 ImageInfiniteLight::uvToDirection(Vec2 uv) const {
    if (layout_ == Layout::EqualArea) return equalAreaSquareToSphere(uv);
    float theta = uv.y * kPi, phi = uv.x * 2 * kPi;
    float st = std::sin(theta);
    return {st * std::cos(phi), st * std::sin(phi), std::cos(theta)};
}

float ImageInfiniteLight::uvPdfToSolidAngle(float pdfUV, Vec2 uv) const {
    if (layout_ == Layout::EqualArea) return pdfUV / (4 * kPi);
    float st = std::sin(uv.y * kPi);
    return st > 0 ? pdfUV / (2 * kPi * kPi * st) : 0.0f;
}

// Nearest texel, as pbrt-v4 does for environment maps.
Spectrum ImageInfiniteLight::lookup(Vec3 wWorld, const SampledWavelengths* lambda) const {
    Vec3 w = normalize(worldFromLight_.inverse().vector(wWorld));
    Vec2 uv = directionToUV(w);
    int x = std::clamp(int(uv.x * image_.width), 0, image_.width - 1);
    int y = std::clamp(int(uv.y * image_.height), 0, image_.height - 1);
    return lambda ? liftIlluminant(image_.get(x, y), *lambda) * scale_ : image_.get(x, y) * scale_;
}

std::optional<LightLiSample> ImageInfiniteLight::sampleLi(const LightSampleContext& ctx, Vec2 u) const {
    float pdfUV;
    Vec2 uv = distribution_.sampleContinuous(u, &pdfUV);
    if (!(pdfUV > 0)) return std::nullopt;
    Vec3 wi = normalize(worldFromLight_.vector(uvToDirection(uv)));
    float pdf = uvPdfToSolidAngle(pdfUV, uv);
    if (!(pdf > 0) || !std::isfinite(pdf)) return std::nullopt;
    return LightLiSample{lookup(wi, ctx.lambda), wi, pdf, ctx.p + wi * (2 * sceneRadius_ + length(ctx.p - sceneCenter_)), {}};
}

float ImageInfiniteLight::pdfLi(const LightSampleContext&, Vec3 wi, const SurfaceInteraction*) const {
    Vec3 w = normalize(worldFromLight_.inverse().vector(wi));
    Vec2 uv = directionToUV(w);
    return uvPdfToSolidAngle(distribution_.pdf(uv), uv);
}

std::optional<LightLeSample> ImageInfiniteLight::sampleLe(Vec2 uPos, Vec2 uDir, const SampledWavelengths* lambda) const {
    auto li = sampleLi(LightSampleContext{sceneCenter_, {}, lambda}, uDir);
    if (!li) return std::nullopt;
    return LightLeSample{li->L, rayFromInfinityDisk(li->wi, sceneCenter_, sceneRadius_, uPos), {},
                         infinityDiskPdf(sceneRadius_), li->pdf, {}};
}

void ImageInfiniteLight::pdfLe(Vec3, Vec3, Vec3 w, float* pdfPos, float* pdfDir) const {
    *pdfPos = infinityDiskPdf(sceneRadius_);
    *pdfDir = pdfLi(LightSampleContext{}, -w, nullptr);
}

// The integral of the radiance over the sphere (texel values times their solid angles:
// 4 pi / N for equal-area texels; latitude-longitude rows shrink towards the poles), times
// the scene disk's area.
Spectrum ImageInfiniteLight::phi() const {
    Spectrum sum;
    int w = image_.width, h = image_.height;
    for (int y = 0; y < h; ++y) {
        Spectrum row;
        for (int x = 0; x < w; ++x) row += image_.get(x, y);
        float omega = layout_ == Layout::EqualArea
                          ? 4 * kPi / (float(w) * float(h))
                          : 2 * kPi / float(w) * (std::cos(kPi * y / h) - std::cos(kPi * (y + 1) / h));
        sum += row * omega;
    }
    return sum * (scale_ * kPi * sceneRadius_ * sceneRadius_);
}

}  // namespace ps
