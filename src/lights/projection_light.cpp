#include "lights/projection_light.h"

#include <algorithm>

namespace ps {

namespace {
constexpr float kHither = 1e-3f;  // directions closer to the screen plane than this emit nothing

Transform flipY() { return Transform::scale({1, -1, 1}); }
}  // namespace

ProjectionLight::Screen ProjectionLight::screenFor(int width, int height, float fovDegrees) {
    float a = float(width) / float(height);
    Screen s{};
    if (a > 1) s = Screen{-a, a, -1, 1, 0};
    else s = Screen{-1, 1, -1 / a, 1 / a, 0};
    s.tanHalfFov = std::tan(radians(fovDegrees) / 2);
    return s;
}

float ProjectionLight::Screen::cos3(float sx, float sy) const {
    float px = sx * tanHalfFov, py = sy * tanHalfFov;
    float c = 1 / std::sqrt(1 + px * px + py * py);
    return c * c * c;
}

float ProjectionLight::Screen::texelCos3(int x, int y, int w, int h) const {
    return cos3(x0 + (x + 0.5f) / w * (x1 - x0), y0 + (y + 0.5f) / h * (y1 - y0));
}

ProjectionLight::ProjectionLight(const Transform& worldFromLight, Image image, float scale, float fovDegrees)
    : Light(LightType::DeltaPosition), frame_(worldFromLight * flipY()), pos_(frame_.position()),
      image_(std::move(image)), scale_(scale), screen_(screenFor(image_.width, image_.height, fovDegrees)) {
    for (float& v : image_.rgb) v = std::max(v, 0.0f);
    int w = image_.width, h = image_.height;
    std::vector<float> weights(size_t(w) * h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            Spectrum c = image_.get(x, y);
            weights[size_t(y) * w + x] = (c.r + c.g + c.b) / 3 * screen_.texelCos3(x, y, w, h);
        }
    distribution_ = Distribution2D(weights, w, h);
}

bool ProjectionLight::screenUV(Vec3 wl, Vec2* uv) const {
    if (!(wl.z >= kHither)) return false;
    float sx = wl.x / (wl.z * screen_.tanHalfFov), sy = wl.y / (wl.z * screen_.tanHalfFov);
    if (!(sx >= screen_.x0 && sx <= screen_.x1 && sy >= screen_.y0 && sy <= screen_.y1)) return false;
    *uv = Vec2((sx - screen_.x0) / (screen_.x1 - screen_.x0), (sy - screen_.y0) / (screen_.y1 - screen_.y0));
    return true;
}

Spectrum ProjectionLight::intensityLight(Vec3 wl, const SampledWavelengths* lambda) const {
    Vec2 uv;
    if (!screenUV(wl, &uv)) return {};
    int x = std::clamp(int(uv.x * image_.width), 0, image_.width - 1);
    int y = std::clamp(int(uv.y * image_.height), 0, image_.height - 1);
    return lambda ? liftIlluminant(image_.get(x, y), *lambda) * scale_ : image_.get(x, y) * scale_;
}

std::optional<LightLiSample> ProjectionLight::sampleLi(const LightSampleContext& ctx, Vec2) const {
    return pointLightLi(pos_, ctx, [&](Vec3 w) { return intensity(w, ctx.lambda); });
}

// A texel by the distribution, a uniform point in it, the direction through that point:
// the density over the plane z = 1 is pdfUV / planeArea, over directions divided by cos^3.
std::optional<LightLeSample> ProjectionLight::sampleLe(Vec2, Vec2 uDir, const SampledWavelengths* lambda) const {
    float pdfUV;
    Vec2 uv = distribution_.sampleContinuous(uDir, &pdfUV);
    if (!(pdfUV > 0)) return std::nullopt;
    float sx = screen_.x0 + uv.x * (screen_.x1 - screen_.x0), sy = screen_.y0 + uv.y * (screen_.y1 - screen_.y0);
    Vec3 wl = normalize(Vec3(sx * screen_.tanHalfFov, sy * screen_.tanHalfFov, 1));
    float pdfDir = frame_.toWorldDensity(pdfUV / (screen_.planeArea() * screen_.cos3(sx, sy)), wl);
    Spectrum I = intensityLight(wl, lambda);
    if (!(pdfDir > 0) || I.isBlack()) return std::nullopt;
    return LightLeSample{I, Ray{pos_, frame_.toWorld(wl)}, {}, 1.0f, pdfDir, {}};
}

void ProjectionLight::pdfLe(Vec3, Vec3, Vec3 w, float* pdfPos, float* pdfDir) const {
    *pdfPos = 0;  // a delta position
    *pdfDir = 0;
    Vec3 wl = frame_.toLight(w);
    Vec2 uv;
    if (!screenUV(wl, &uv)) return;
    float sx = wl.x / (wl.z * screen_.tanHalfFov), sy = wl.y / (wl.z * screen_.tanHalfFov);
    *pdfDir = frame_.toWorldDensity(distribution_.pdf(uv) / (screen_.planeArea() * screen_.cos3(sx, sy)), wl);
}

std::optional<LightBounds> ProjectionLight::bounds() const {
    double sum = 0;
    for (int y = 0; y < image_.height; ++y)
        for (int x = 0; x < image_.width; ++x) sum += image_.get(x, y).maxComponent();
    float meanI = float(sum / (double(image_.width) * image_.height)) * scale_;
    // The frustum's four edges, carried to the world (the transform may shear it), bound the
    // cone about the axis; an edge at or beyond 90 degrees from it leaves every direction.
    Vec3 axis = frame_.toWorld({0, 0, 1});
    float cosTheta = 1;
    for (float sx : {screen_.x0, screen_.x1})
        for (float sy : {screen_.y0, screen_.y1}) {
            Vec3 edge = frame_.toWorld(normalize(Vec3(sx * screen_.tanHalfFov, sy * screen_.tanHalfFov, 1)));
            cosTheta = std::min(cosTheta, dot(axis, edge));
        }
    if (!(cosTheta > 0)) cosTheta = -1;
    // A margin of 1e-3 radians of emission beyond the cone, for rounding (see SpotLight::bounds).
    return LightBounds(Bounds3(pos_), axis, 4 * kPi * meanI, cosTheta, std::cos(1e-3f), false);
}

Spectrum ProjectionLight::phi() const {
    int w = image_.width, h = image_.height;
    Spectrum sum;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) sum += image_.get(x, y) * screen_.texelCos3(x, y, w, h);
    return sum * (scale_ * screen_.planeArea() / (float(w) * float(h)));
}

}  // namespace ps
