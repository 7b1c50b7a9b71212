#include "camera/lens_system.h"

#include <tbb/parallel_for.h>

#include <cmath>

#include "materials/fresnel.h"
#include "mc/sobol.h"
#include "util/error.h"

namespace ps {

namespace {

constexpr int kPupilSegments = 64;  // exit-pupil bounds from the film centre to a corner

// Lens space is camera space with z negated: the film at z = 0, the elements at negative z.
Ray flipZ(const Ray& r) { return Ray{{r.o.x, r.o.y, -r.o.z}, {r.d.x, r.d.y, -r.d.z}}; }

// The ray's hit with the spherical interface of signed radius R centred on the axis at
// zCentre. Of the sphere's two hits the interface is the one on the vertex's cap: the
// nearer when the ray travels towards the centre's side (d.z and R of one sign), else the
// farther. n faces the incoming ray.
bool hitSphericalInterface(float R, float zCentre, const Ray& r, float* t, Vec3* n) {
    double ox = r.o.x, oy = r.o.y, oz = double(r.o.z) - zCentre;
    double a = double(r.d.x) * r.d.x + double(r.d.y) * r.d.y + double(r.d.z) * r.d.z;
    double b = 2 * (r.d.x * ox + r.d.y * oy + r.d.z * oz);
    double c = ox * ox + oy * oy + oz * oz - double(R) * R;
    double disc = b * b - 4 * a * c;
    if (!(a > 0) || !(disc >= 0)) return false;
    // The stable pair of roots.
    double q = -0.5 * (b + std::copysign(std::sqrt(disc), b));
    double t0 = q / a, t1 = q != 0 ? c / q : t0;
    if (t0 > t1) std::swap(t0, t1);
    bool nearer = (r.d.z > 0) != (R < 0);
    double th = nearer ? t0 : t1;
    if (!(th >= 0)) return false;
    *t = float(th);
    Vec3 p(float(ox + th * r.d.x), float(oy + th * r.d.y), float(oz + th * r.d.z));
    *n = normalize(p);
    if (dot(*n, r.d) > 0) *n = -*n;
    return true;
}

// The hit with the plane z = zPlane, if ahead of the ray.
bool hitStop(float zPlane, const Ray& r, float* t) {
    *t = (zPlane - r.o.z) / r.d.z;
    return *t >= 0 && std::isfinite(*t);
}

// The first n points of the Halton sequence in bases 2 and 3, shared by every film
// segment's search: base 2 by bit reversal, base 3 by counting in ternary.
std::vector<Vec2> haltonPoints(int n) {
    std::vector<Vec2> pts(size_t(std::max(n, 0)));
    int digits[40] = {};
    double value = 0, scale[40];
    scale[0] = 1.0 / 3;
    for (int k = 1; k < 40; ++k) scale[k] = scale[k - 1] / 3;
    for (int i = 0; i < n; ++i) {
        pts[size_t(i)] = {float(reverseBits32(uint32_t(i)) * 0x1p-32), float(value)};
        for (int k = 0; k < 40; ++k) {  // value of i + 1: add one with carries
            if (digits[k] < 2) {
                ++digits[k];
                value += scale[k];
                break;
            }
            digits[k] = 0;
            value -= 2 * scale[k];
        }
    }
    return pts;
}

}  // namespace

LensSystem::LensSystem(Params p)
    : interfaces_(std::move(p.interfaces)), mask_(std::move(p.mask)), filmDiagonal_(p.filmDiagonal),
      xRes_(p.xRes), yRes_(p.yRes) {
    if (interfaces_.empty()) throw InputError("the lens description has no interfaces");
    if (!(p.filmDiagonal > 0)) throw InputError("the film diagonal must be positive");
    if (!(p.apertureDiameter > 0)) throw InputError("\"aperturediameter\" must be positive");
    for (LensInterface& e : interfaces_) {
        if (!e.isStop()) continue;
        if (p.apertureDiameter / 2 > e.apertureRadius) apertureClamped_ = true;
        else e.apertureRadius = p.apertureDiameter / 2;
    }
    // The film's physical extent: the diagonal split by the aspect ratio.
    float aspect = float(yRes_) / float(xRes_);
    float w = std::sqrt(filmDiagonal_ * filmDiagonal_ / (1 + aspect * aspect));
    filmSize_ = {w, aspect * w};

    cardinal_ = thickLens();
    interfaces_.back().thickness = focusedRearThickness(p.focusDistance);

    const std::vector<Vec2> halton = haltonPoints(std::max(1, p.pupilSamplesPerSegment));
    pupil_.resize(kPupilSegments);
    tbb::parallel_for(0, kPupilSegments, [&](int i) {
        float r0 = float(i) / kPupilSegments * filmDiagonal_ / 2, r1 = float(i + 1) / kPupilSegments * filmDiagonal_ / 2;
        pupil_[size_t(i)] = boundExitPupil(r0, r1, halton);
    });
}

float LensSystem::frontZ() const {
    float z = 0;
    for (const LensInterface& e : interfaces_) z += e.thickness;
    return z;
}

float LensSystem::traceFromFilm(const Ray& rFilm, Ray* out) const {
    Ray r = flipZ(rFilm);
    float z = 0, weight = 1;
    for (int i = int(interfaces_.size()) - 1; i >= 0; --i) {
        const LensInterface& e = interfaces_[size_t(i)];
        z -= e.thickness;
        float t;
        Vec3 n;
        if (e.isStop() ? !hitStop(z, r, &t) : !hitSphericalInterface(e.curvatureRadius, z + e.curvatureRadius, r, &t, &n))
            return 0;
        Vec3 p = r.o + r.d * t;
        if (e.isStop() && mask_) {
            weight = mask_->lookup({(p.x / e.apertureRadius + 1) / 2, (p.y / e.apertureRadius + 1) / 2});
            if (!(weight > 0)) return 0;
        } else if (!(p.x * p.x + p.y * p.y <= e.apertureRadius * e.apertureRadius)) {
            return 0;
        }
        r.o = p;
        if (!e.isStop()) {
            // Leaving the medium behind interface i for the one in front of it.
            float etaOut = i > 0 ? interfaces_[size_t(i) - 1].eta : 1.0f;
            Vec3 wt;
            if (!refract(normalize(-r.d), n, etaOut / e.eta, nullptr, &wt)) return 0;
            r.d = wt;
        }
    }
    if (out) *out = flipZ(r);
    return weight;
}

bool LensSystem::traceFromScene(const Ray& rScene, Ray* out) const {
    Ray r = flipZ(rScene);
    float z = -frontZ();
    for (size_t i = 0; i < interfaces_.size(); ++i) {
        const LensInterface& e = interfaces_[i];
        float t;
        Vec3 n;
        if (e.isStop() ? !hitStop(z, r, &t) : !hitSphericalInterface(e.curvatureRadius, z + e.curvatureRadius, r, &t, &n))
            return false;
        Vec3 p = r.o + r.d * t;
        if (!(p.x * p.x + p.y * p.y <= e.apertureRadius * e.apertureRadius)) return false;
        r.o = p;
        if (!e.isStop()) {
            float etaIn = i > 0 ? interfaces_[i - 1].eta : 1.0f;
            Vec3 wt;
            if (!refract(normalize(-r.d), n, e.eta / etaIn, nullptr, &wt)) return false;
            r.d = wt;
        }
        z += e.thickness;
    }
    if (out) *out = flipZ(r);
    return true;
}

LensSystem::Cardinal LensSystem::thickLens() const {
    // A ray parallel to the axis at a small height (a thousandth of the film diagonal),
    // traced through the lens from each side: where it crosses the axis is the focal point,
    // where its extension meets the incoming ray's height the principal plane.
    const float h = 0.001f * filmDiagonal_;
    auto cardinal = [](const Ray& in, const Ray& outR, float* principal, float* focal) {
        float tf = -outR.o.x / outR.d.x, tp = (in.o.x - outR.o.x) / outR.d.x;
        *focal = -(outR.o.z + tf * outR.d.z);
        *principal = -(outR.o.z + tp * outR.d.z);
        return std::isfinite(*focal) && std::isfinite(*principal);
    };
    Cardinal c;
    const std::string why = "cannot trace a ray parallel to the axis through the lens system for the thick-lens "
                            "approximation (is the aperture stop extremely small?)";
    Ray fromScene{{h, 0, frontZ() + 1}, {0, 0, -1}}, toFilm;
    if (!traceFromScene(fromScene, &toFilm)) throw InputError(why);
    Ray fromFilm{{h, 0, rearZ() - 1}, {0, 0, 1}}, toScene;
    if (traceFromFilm(fromFilm, &toScene) == 0) throw InputError(why);
    if (!cardinal(fromScene, toFilm, &c.principal[0], &c.focal[0]) ||
        !cardinal(fromFilm, toScene, &c.principal[1], &c.focal[1]))
        throw InputError("the lens system does not focus parallel rays (it is afocal)");
    return c;
}

float LensSystem::focusedRearThickness(float focusDistance) const {
    // Move the lens by delta so the thick lens images the plane at focusDistance from the
    // film onto the film: 1/(object distance from the scene-side principal plane) + 1/(image
    // distance from the film-side one) = 1/f, a quadratic in delta.
    const float* pz = cardinal_.principal;
    float f = cardinal_.focal[0] - pz[0];
    float z = -focusDistance;
    float c = (pz[1] - z - pz[0]) * (pz[1] - z - 4 * f - pz[0]);
    if (!(c > 0))
        throw InputError("\"focusdistance\" " + std::to_string(focusDistance) +
                         " is too short for this lens (it cannot focus closer)");
    float delta = (pz[1] - z + pz[0] - std::sqrt(c)) / 2;
    float t = interfaces_.back().thickness + delta;
    if (!(t > 0) || !std::isfinite(t))
        throw InputError("focusing at \"focusdistance\" " + std::to_string(focusDistance) +
                         " would put the film inside the lens system");
    return t;
}

PupilBounds LensSystem::boundExitPupil(float r0, float r1, const std::vector<Vec2>& halton) const {
    // Rear-element points of a square 1.5 times its radius on each side, paired with film
    // points along the segment [r0, r1] of the x axis. Points inside the bounds found so
    // far need no tracing.
    PupilBounds b;
    const float half = 1.5f * rearRadius();
    const int samples = int(halton.size());
    for (int i = 0; i < samples; ++i) {
        float s = (i + 0.5f) / float(samples);
        Vec3 pFilm((1 - s) * r0 + s * r1, 0, 0);
        Vec2 u = halton[size_t(i)];
        Vec2 pRear(-half + 2 * half * u.x, -half + 2 * half * u.y);
        if (b.contains(pRear)) continue;
        if (traceFromFilm(Ray{pFilm, Vec3(pRear.x, pRear.y, rearZ()) - pFilm}, nullptr) > 0) {
            b.lo = {std::min(b.lo.x, pRear.x), std::min(b.lo.y, pRear.y)};
            b.hi = {std::max(b.hi.x, pRear.x), std::max(b.hi.y, pRear.y)};
        }
    }
    if (b.empty()) return b;
    // Widen by twice the sample spacing: the points found lie just inside the pupil's edge.
    float pad = 2 * (2 * half * std::sqrt(2.0f)) / std::sqrt(float(samples));
    b.lo = b.lo - Vec2(pad, pad);
    b.hi = b.hi + Vec2(pad, pad);
    return b;
}

Vec3 LensSystem::filmPoint(Vec2 pRaster) const {
    float sx = pRaster.x / float(xRes_), sy = pRaster.y / float(yRes_);
    // The lens inverts the image: the scene's top left (camera -x, +y) is imaged at film
    // (+x, -y), so that is where the raster's top-left corner lies.
    return {-(-filmSize_.x / 2 + sx * filmSize_.x), -filmSize_.y / 2 + sy * filmSize_.y, 0};
}

float LensSystem::generateRay(Vec2 pRaster, Vec2 u, Ray* out) const {
    Vec3 pFilm = filmPoint(pRaster);
    float rFilm = std::sqrt(pFilm.x * pFilm.x + pFilm.y * pFilm.y);
    float seg = rFilm / (filmDiagonal_ / 2) * kPupilSegments;
    int idx = seg < float(kPupilSegments - 1) ? int(seg) : kPupilSegments - 1;
    const PupilBounds& b = pupil_[size_t(idx)];
    if (b.empty()) return 0;
    // The bounds were found along +x: rotate the sample to the film point's azimuth.
    Vec2 pl((1 - u.x) * b.lo.x + u.x * b.hi.x, (1 - u.y) * b.lo.y + u.y * b.hi.y);
    float sinT = rFilm != 0 ? pFilm.y / rFilm : 0, cosT = rFilm != 0 ? pFilm.x / rFilm : 1;
    Vec3 pRear(cosT * pl.x - sinT * pl.y, sinT * pl.x + cosT * pl.y, rearZ());
    Ray rFilmRay{pFilm, pRear - pFilm};
    Ray r;
    float w = traceFromFilm(rFilmRay, &r);
    if (!(w > 0)) return 0;
    float cosTheta = normalize(rFilmRay.d).z, cos2 = cosTheta * cosTheta;
    // Area sampling over the bounds (pdf 1/area) of E = integral of L cos^4 / rearZ^2 dA.
    w *= cos2 * cos2 * b.area() / (rearZ() * rearZ());
    if (!std::isfinite(w)) return 0;
    *out = r;
    return w;
}

}  // namespace ps
