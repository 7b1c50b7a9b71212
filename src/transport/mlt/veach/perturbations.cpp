#include "transport/mlt/veach/perturbations.h"

#include <cmath>
#include <limits>

namespace ps {

Perturbations::Perturbations(const PathSpace& space, const PerturbationSizes& sizes) : space_(space), sizes_(sizes) {
    const Camera::Params& c = space.scene().camera().params();
    r2_ = std::sqrt(sizes.imageFraction * double(c.xRes) * double(c.yRes) / kPi);
}

// The lens ray and every specular chain after it, up to a D vertex that connects to its
// predecessor (or the light): the lens perturbation when that is the first chain's end,
// the multi-chain perturbation when a chain ends on a D vertex after a specular one.
namespace {

// The index where the retraced part of x ends (the D vertex joined to its predecessor, or 0
// for a light reached by the last chain), or -1; *chains receives the number of chains.
int retracedEnd(const MltPath& x, const PathSpace& space, int* chains) {
    *chains = 0;
    for (int m = int(x.size()) - 2;; --m) {
        ++*chains;
        m = space.specularChainEnd(x, m);
        if (m <= 0 || space.connectible(x, m - 1)) return m;  // else a specular predecessor: the next chain starts there
    }
}

// T's Jacobian part for the retraced vertices [end, k - 1] of z (see perturbations.h).
double retracedDensity(const MltPath& z, const PathSpace& space, int end) {
    const int k = int(z.size()) - 1;
    double p = 1;
    for (int i = k - 1; i >= end && p > 0; --i)
        p *= (i + 1 < k && z[size_t(i + 1)].isNonSpecularSurface())
                 ? PathSpace::areaFactor(z, i + 1, i)
                 : space.cameraDensity(z, i, PathSpace::Lobes::Forced);
    return p;
}

}  // namespace

bool Perturbations::lensApplies(const MltPath& x) const {
    int chains;
    return space_.pinhole() && retracedEnd(x, space_, &chains) >= 0 && chains == 1;
}

bool Perturbations::multiChainApplies(const MltPath& x) const {
    int chains;
    return space_.pinhole() && retracedEnd(x, space_, &chains) >= 0 && chains > 1;
}

Vec3 Perturbations::perturbDirection(Vec3 w, Rng& rng) const {
    // theta with density proportional to 1 / theta on [theta1, theta2], phi uniform: a
    // density in solid angle that depends only on the angle between the directions.
    const double theta = sizes_.theta1 * std::pow(sizes_.theta2 / sizes_.theta1, rng.uniformDouble());
    const double phi = 2 * kPi * rng.uniformDouble();
    const Frame f = Frame::fromNormal(w);
    const double st = std::sin(theta);
    return normalize(f.toWorld(Vec3(float(st * std::cos(phi)), float(st * std::sin(phi)), float(std::cos(theta)))));
}

bool Perturbations::lens(const MltPath& x, Vec2 rasterX, Rng& rng, ScratchBuffer& arena, PathStats& stats, MltPath& y,
                         double* ratio) const {
    const int k = int(x.size()) - 1;
    int chains;
    const int end = retracedEnd(x, space_, &chains);
    if (end < 0 || !space_.pinhole()) return false;
    // The image point's offset: length with density proportional to 1 / r, uniform angle.
    const double r = sizes_.r1 * std::pow(r2_ / sizes_.r1, rng.uniformDouble());
    const double phi = 2 * kPi * rng.uniformDouble();
    CameraSample cs;
    cs.pFilm = Vec2(float(rasterX.x + r * std::cos(phi)), float(rasterX.y + r * std::sin(phi)));
    cs.pLens = Vec2(0.5f, 0.5f);
    float pdfPos, pdfDir;
    // The path keeps its time (and so its lens position).
    Ray ray = space_.scene().camera().generateRayAt(cs, x[size_t(k)].time);
    space_.scene().camera().pdfWe(ray, &pdfPos, &pdfDir);
    if (!(pdfDir > 0)) return false;  // off the film

    // Spectral mode: the whole path at nearby wavelengths, the retraced chain following them.
    const SampledWavelengths lambda = space_.perturbWavelengths(x[0].lambda, rng);
    PathSpace::copyAt(x, lambda, arena, y);
    for (int i = k - 1; i >= end; --i) {
        MltVertex v;
        // x0 may lie at infinity. Through media the retrace samples no flights (media only
        // attenuate: f's transmittance), so T has no flight densities (Lobes::Forced).
        if (!space_.trace(ray, lambda, arena, stats, v, i == 0, space_.mediumFrom(y[size_t(i + 1)], ray.d)))
            return false;
        const MltVertex& old = x[size_t(i)];
        if (i > 0 && old.isSpecularSurface() && !v.takeSpecularRole()) return false;
        y[size_t(i)] = v;
        if (i == 0) {
            if (!v.light) return false;  // the last chain must end on an emitter
        } else if (old.isSpecularSurface()) {
            if (!space_.followSpecular(v, ray, PathSpace::reflects(x, i), TransportMode::Radiance, ray)) return false;
        } else {
            if (!v.isNonSpecularSurface()) return false;
            if (i > end) ray = spawnRay(v.p, v.ng, perturbDirection(directionTo(old, x[size_t(i - 1)]), rng), v.time);
        }
    }
    if (end > 0 && !space_.visible(y[size_t(end - 1)], y[size_t(end)], stats)) return false;
    const double py = retracedDensity(y, space_, end);
    if (!(py > 0)) return false;
    *ratio = retracedDensity(x, space_, end) / py;
    return true;
}

bool Perturbations::causticApplies(const MltPath& x) const {
    const int k = int(x.size()) - 1;
    if (k < 3 || !x[size_t(k - 1)].isNonSpecularSurface() || !x[size_t(k - 2)].isSpecularSurface()) return false;
    int m = k - 2;
    while (m > 0 && x[size_t(m)].isSpecularSurface()) --m;
    return m == 0 || x[size_t(m)].isNonSpecularSurface();
}

bool Perturbations::caustic(const MltPath& x, Rng& rng, ScratchBuffer& arena, PathStats& stats, MltPath& y,
                            double* ratio) const {
    if (!causticApplies(x)) return false;
    const int k = int(x.size()) - 1;
    int m = k - 2;
    while (m > 0 && x[size_t(m)].isSpecularSurface()) --m;
    // Spectral mode: the whole path at nearby wavelengths, the retraced chain following them.
    const SampledWavelengths lambda = space_.perturbWavelengths(x[0].lambda, rng);
    PathSpace::copyAt(x, lambda, arena, y);
    const MltVertex& from = y[size_t(m)];
    Ray ray;
    if (atInfinity(from)) {
        // x0 is a direction, which stays; its ray, a point of the disk at infinity facing
        // it, moves by an offset of length in [theta1, theta2] times the scene's radius
        // (density proportional to 1 / length, uniform azimuth): symmetric, and of unit
        // density in the disk's area, which areaFactor(z, 0, 1) turns into x1's.
        const Scene& scene = space_.scene();
        const double R = scene.boundsRadius();
        const double r = R * sizes_.theta1 * std::pow(sizes_.theta2 / sizes_.theta1, rng.uniformDouble());
        const double phi = 2 * kPi * rng.uniformDouble();
        const Frame f = Frame::fromNormal(from.ng);
        const Vec3 x1 = x[1].p;
        // Back along the direction past the scene's bounding sphere, then sideways.
        const float back = float(2 * R) + length(x1 - scene.boundsCenter());
        const Vec3 o = x1 - from.ng * back + f.s * float(r * std::cos(phi)) + f.t * float(r * std::sin(phi));
        ray = Ray{o, from.ng, std::numeric_limits<float>::infinity(), from.time};
    } else {
        ray = spawnRay(from.p, from.ng, perturbDirection(directionTo(from, x[size_t(m + 1)]), rng), from.time);
    }
    for (int i = m + 1; i <= k - 1; ++i) {
        MltVertex v;
        if (!space_.trace(ray, lambda, arena, stats, v, false, space_.mediumFrom(y[size_t(i - 1)], ray.d))) return false;
        if (i < k - 1 && !v.takeSpecularRole()) return false;
        y[size_t(i)] = v;
        if (i < k - 1) {
            if (!space_.followSpecular(v, ray, PathSpace::reflects(x, i), TransportMode::Importance, ray)) return false;
        } else if (!v.isNonSpecularSurface()) {
            return false;
        }
    }
    if (!space_.visible(y[size_t(k - 1)], y[size_t(k)], stats)) return false;
    // The Jacobians: a unit direction density at x_m, then the retraced vertices' with
    // forced lobes.
    auto density = [&](const MltPath& z) {
        double p = PathSpace::areaFactor(z, m, m + 1);
        for (int i = m + 2; i <= k - 1 && p > 0; ++i) p *= space_.lightDensity(z, i, PathSpace::Lobes::Forced);
        return p;
    };
    const double py = density(y);
    if (!(py > 0)) return false;
    *ratio = density(x) / py;
    return true;
}

}  // namespace ps
