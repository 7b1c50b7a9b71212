#include "transport/mlt/veach/path_space.h"

#include <cmath>
#include <limits>

#include "materials/fresnel.h"
#include "math/warp.h"

namespace ps {

namespace {

Vec3 unitTo(const MltVertex& from, const MltVertex& to) { return directionTo(from, to); }

// The ray leaving the lens vertex towards `to`, at the path's time (where the camera is then).
Ray fromLens(const MltVertex& lens, const MltVertex& to) {
    return Ray{lens.p, unitTo(lens, to), std::numeric_limits<float>::infinity(), lens.time};
}

// The mirror direction of a local direction w about the shading normal (0, 0, 1).
Vec3 mirror(Vec3 w) { return reflect(w, Vec3(0, 0, 1)); }

// The wavelengths a vertex's BxDF and emission are evaluated at: null in RGB mode (a path's
// wavelengths are all zero there).
const SampledWavelengths* wavelengthsOf(const MltVertex& v) { return v.lambda.lambda[0] > 0 ? &v.lambda : nullptr; }

// The BxDF of hit si at the path's wavelengths, and whether it is dispersive (it asked to
// keep lambda[0] alone; the path's own wavelengths are not changed: contribution applies it).
const BxDF* bxdfAt(SurfaceInteraction& si, const SampledWavelengths& lambda, ScratchBuffer& arena, bool* dispersive) {
    if (!(lambda.lambda[0] > 0)) {
        *dispersive = false;
        return surfaceBxDF(si, arena);
    }
    SampledWavelengths copy = lambda;
    const BxDF* b = surfaceBxDF(si, arena, &copy);
    *dispersive = copy.terminationRequests != lambda.terminationRequests;
    return b;
}

// The normal a ray leaving v is offset along (the lens and points have none).
Vec3 offsetNormal(const MltVertex& v) { return v.kind == MltVertex::Kind::Lens ? Vec3() : v.ng; }

// The area density at `to` of a direction density pdfDir at `from`. A vertex at infinity
// keeps its solid-angle density; from one, pdfDir is a density per unit area of the disk at
// infinity facing its direction, which projects onto `to` with |cos| (path_space.h).
double toArea(double pdfDir, const MltVertex& from, const MltVertex& to) {
    if (atInfinity(to)) return pdfDir;
    if (atInfinity(from)) return pdfDir * cosAt(to, from.ng);
    Vec3 d = to.p - from.p;
    double d2 = double(lengthSquared(d));
    if (!(d2 > 0)) return 0;
    return pdfDir * cosAt(to, d * float(1 / std::sqrt(d2))) / d2;
}

}  // namespace

PathSpace::PathSpace(const Scene& scene, int maxDepth) : scene_(scene), maxDepth_(maxDepth) {
    const Camera::Params& c = scene.camera().params();
    pinhole_ = !(c.lensRadius > 0);
    lensReachable_ = scene.camera().hasLensDisk();
    margin_ = scene.filter().radius();
    filmSize_ = Vec2(float(c.xRes) + 2 * margin_.x, float(c.yRes) + 2 * margin_.y);
    if (scene.settings().spectral) sensor_.emplace(scene.settings());
}

void PathSpace::bsdf(const MltVertex& v, Vec3 wo, Vec3 wi, TransportMode mode, Spectrum* f, float* pdf,
                     float* jacobian) const {
    const Vec3 woL = v.frame.toLocal(wo), wiL = v.frame.toLocal(wi);
    if (jacobian) *jacobian = 1;
    if (v.mixed) {
        // PathSpace's own sampling of a layered BxDF (MltVertex::mixed): its density is exact.
        const float R = v.bxdf->coatingMirrorReflectance(woL);
        if (f) *f = Spectrum();
        if (pdf) *pdf = 0;
        if (v.delta) {
            if (dot(mirror(woL), wiL) > 1 - 1e-4f && wiL.z != 0) {
                if (f) *f = Spectrum(R / std::fabs(wiL.z));
                if (pdf) *pdf = R;
            }
        } else if (woL.z * wiL.z > 0) {
            if (f) *f = v.bxdf->f(woL, wiL, mode);
            if (pdf) *pdf = (1 - R) * std::fabs(wiL.z) * kInvPi;
        }
        return;
    }
    if (!v.delta) {
        if (f) *f = v.bxdf->f(woL, wiL, mode);
        if (pdf) *pdf = v.bxdf->pdf(woL, wiL, mode);
        return;
    }
    // A specular vertex: the lobe (reflection or transmission) whose direction is wi. Each
    // lobe is found by sampling with the lobe choice at either end of [0, 1).
    if (f) *f = Spectrum();
    if (pdf) *pdf = 0;
    for (float uc : {0.0f, 0x1.fffffep-1f}) {
        auto s = v.bxdf->sample(woL, uc, Vec2(0.5f, 0.5f), mode);
        if (s && dot(s->wi, wiL) > 1 - 1e-4f) {
            if (f) *f = s->f;
            if (pdf) *pdf = s->pdf;
            // Étendue, eta^2 |cos| d(omega), is the same on both sides of a refraction (thesis
            // §5.2); from the sampled directions.
            if (jacobian && s->isTransmission()) *jacobian = s->eta * s->eta * std::fabs(s->wi.z) / std::fabs(woL.z);
            return;
        }
    }
}

Spectrum PathSpace::contribution(const MltPath& x, Vec2* pRaster, Rng* rng) const {
    const int k = int(x.size()) - 1;
    if (k < 1 || !x[0].light || x[k].kind != MltVertex::Kind::Lens) return {};
    // A point light seen directly would be a point of finite energy on the film, which no
    // other integrator renders (a camera ray never hits it; BDPT has no such strategy).
    if (k == 1 && x[0].isDeltaLight()) return {};
    auto geometry = [](const MltVertex& a, const MltVertex& b) {
        // An edge to infinity: the cosine at its finite end alone (solid-angle measure).
        if (atInfinity(a)) return cosAt(b, a.ng);
        Vec3 d = b.p - a.p;
        float d2 = lengthSquared(d);
        if (!(d2 > 0)) return 0.0f;
        Vec3 w = d / std::sqrt(d2);
        return cosAt(a, w) * cosAt(b, w) / d2;
    };
    Spectrum f = emitted(x[0], x[1]) * geometry(x[0], x[1]);
    for (int i = 1; i < k && !f.isBlack(); ++i) {
        const MltVertex& v = x[size_t(i)];
        const Vec3 wi = unitTo(v, x[size_t(i - 1)]), wo = unitTo(v, x[size_t(i + 1)]);
        if (v.isMedium()) {
            // sigma_s times the phase function (symmetric: no adjoint), no cosine (volume measure).
            const Spectrum sigmaS = v.mediumAbove->at(v.p, wavelengthsOf(v)).sigmaS;
            f *= sigmaS * v.mediumAbove->phase().p(wi, wo) * geometry(v, x[size_t(i + 1)]);
            continue;
        }
        if (v.kind != MltVertex::Kind::Surface || !v.bxdf) return {};
        Spectrum fs;
        bsdf(v, wo, wi, TransportMode::Radiance, &fs, nullptr);
        // The path tracer's shading cosine |wi.ns| in place of the geometric one in G.
        const float cosG = cosAt(v, wi);
        if (!(cosG > 0)) return {};
        f *= fs * (std::fabs(dot(wi, v.ns)) / cosG) * geometry(v, x[size_t(i + 1)]);
    }
    if (scene_.hasMedia())
        for (int i = 0; i < k && !f.isBlack(); ++i) f *= edgeTransmittance(x[size_t(i)], x[size_t(i + 1)], rng);
    if (f.isBlack()) return {};
    const float We = scene_.camera().We(fromLens(x[size_t(k)], x[size_t(k - 1)]), pRaster);
    f *= We;
    if (sensor_) {
        SampledWavelengths lambda = x[size_t(k)].lambda;
        for (const MltVertex& v : x)
            if (v.dispersive) lambda.terminateSecondary();
        f = sensor_->toRendering(f, lambda);
    }
    return f.isFinite() ? f : Spectrum();
}

double PathSpace::lightDensity(const MltPath& x, int i, Lobes lobes) const {
    const int k = int(x.size()) - 1;
    if (i < 0 || i > k) return 0;
    const MltVertex& v = x[size_t(i)];
    // The lens from the light side: a ray scattered at x_{k-1} that crosses a thin lens.
    if (v.kind == MltVertex::Kind::Lens && !(i == k && i >= 2 && lensReachable_)) return 0;
    if (i == 0) {
        if (!v.light || k < 1) return 0;
        if (atInfinity(v)) return infinityDensity(v);
        float pdfPos, pdfDir;
        v.light->pdfLe(v.p, v.ng, unitTo(v, x[1]), &pdfPos, &pdfDir);
        // A point light's position is a delta of unit weight (the light reports no density
        // there, as no other strategy can reach it).
        if (pdfPos == 0 && v.isDeltaLight()) pdfPos = 1;
        return double(scene_.lightPmf(v.light)) * pdfPos;
    }
    const MltVertex& u = x[size_t(i - 1)];
    const Vec3 w = unitTo(u, v);
    float pdfDir = 0;
    if (i == 1) {
        float pdfPos;
        u.light->pdfLe(u.p, u.ng, w, &pdfPos, &pdfDir);
        // From infinity: the disk's area density, projected onto v by toArea.
        if (atInfinity(u)) pdfDir = pdfPos;
    } else if (u.isMedium()) {
        pdfDir = u.mediumAbove->phase().pdf(unitTo(u, x[size_t(i - 2)]), w);
    } else {
        if (u.kind != MltVertex::Kind::Surface || !u.bxdf) return 0;
        float jacobian;
        bsdf(u, unitTo(u, x[size_t(i - 2)]), w, TransportMode::Importance, nullptr, &pdfDir, &jacobian);
        if (u.delta && lobes == Lobes::Forced && pdfDir > 0) pdfDir = 1;
        // A specular lobe's delta: f's and cameraDensity's are in the light-side direction
        // (sampled from the camera side), this one in the camera-side direction w. Through
        // a refraction the two measures differ by the Jacobian of the lobe's map (thesis
        // §5.2: eta^2 |cos| d(omega) is conserved), so the delta is carried over to f's.
        // Without it a path through refractions whose angles do not cancel (a medium or a
        // surface inside a dielectric) had other densities from each side: mlt 1-8% too bright.
        pdfDir *= jacobian;
    }
    const double flight = scene_.hasMedia() && lobes == Lobes::Sampled ? flightDensity(u, v) : 1.0;
    return toArea(pdfDir, u, v) * flight;
}

double PathSpace::cameraDensity(const MltPath& x, int i, Lobes lobes) const {
    const int k = int(x.size()) - 1;
    if (i < 0 || i > k || k < 1) return 0;
    const MltVertex& v = x[size_t(i)];
    // Walks from the lens reach neither a point light nor the lens itself.
    if (v.isDeltaLight() || (i < k && v.kind == MltVertex::Kind::Lens)) return 0;
    if (i == k) {
        float pdfPos, pdfDir;
        scene_.camera().pdfWe(fromLens(v, x[size_t(k - 1)]), &pdfPos, &pdfDir);
        return pdfPos;
    }
    const MltVertex& u = x[size_t(i + 1)];
    const Vec3 w = unitTo(u, v);
    float pdfDir = 0;
    if (i + 1 == k) {
        float pdfPos;
        scene_.camera().pdfWe(fromLens(u, v), &pdfPos, &pdfDir);
    } else if (u.isMedium()) {
        pdfDir = u.mediumAbove->phase().pdf(unitTo(u, x[size_t(i + 2)]), w);
    } else {
        if (u.kind != MltVertex::Kind::Surface || !u.bxdf) return 0;
        bsdf(u, unitTo(u, x[size_t(i + 2)]), w, TransportMode::Radiance, nullptr, &pdfDir);
        if (u.delta && lobes == Lobes::Forced && pdfDir > 0) pdfDir = 1;
    }
    const double flight = scene_.hasMedia() && lobes == Lobes::Sampled ? flightDensity(u, v) : 1.0;
    return toArea(pdfDir, u, v) * flight;
}

bool PathSpace::connectible(const MltPath& x, int i) const {
    const int k = int(x.size()) - 1;
    // At infinity: the join is a shadow ray along the direction (a distant light's too).
    if (i == 0) return x[0].light != nullptr;
    if (i == k) return x[size_t(k)].kind == MltVertex::Kind::Lens;
    return x[size_t(i)].isNonSpecularSurface() || x[size_t(i)].isMedium();
}

int PathSpace::specularChainEnd(const MltPath& x, int from) const {
    int m = from;
    while (m > 0 && x[size_t(m)].isSpecularSurface()) --m;
    if (m == 0) return x[0].light && !x[0].isDeltaLight() ? 0 : -1;
    return x[size_t(m)].isNonSpecularSurface() ? m : -1;
}

bool PathSpace::canContinue(int size, TransportMode mode) const {
    if (size == 0) return true;
    if (size == 1) return mode == TransportMode::Radiance && pinhole_;
    return true;
}

bool PathSpace::visible(const MltVertex& a, const MltVertex& b, PathStats& stats) const {
    ++stats.shadowRays;
    // Through media, `interface` shapes are crossed (the transmittance is f's).
    if (scene_.hasMedia()) return visibleThroughMedia(a, b, stats);
    if (atInfinity(a) || atInfinity(b)) {
        const MltVertex& from = atInfinity(a) ? b : a;
        return !scene_.occluded(spawnRay(from.p, offsetNormal(from), directionTo(from, atInfinity(a) ? a : b), from.time));
    }
    const Ray ray = shadowRay(a.p, offsetNormal(a), b, a.time);
    return !(ray.tMax > 0) || !scene_.occluded(ray);
}

Ray PathSpace::shadowRay(Vec3 from, Vec3 fromNg, const MltVertex& to, float time) {
    Ray ray = spawnRayTo(from, fromNg, to.p, time);
    if (to.kind != MltVertex::Kind::Lens) {
        // The offset a ray leaving `to` towards `from` would get (zero at a point: a medium
        // vertex, a point light).
        const float margin = length(offsetRayOrigin(to.p, to.ng, -ray.d) - to.p), len = length(ray.d);
        ray.tMax = len > margin ? std::min(ray.tMax, 1 - margin / len) : 0.0f;
    }
    return ray;
}

double PathSpace::areaFactor(const MltPath& x, int from, int to) { return toArea(1.0, x[size_t(from)], x[size_t(to)]); }

bool PathSpace::reflects(const MltPath& x, int i) {
    const MltVertex& v = x[size_t(i)];
    return dot(directionTo(v, x[size_t(i - 1)]), v.ng) * dot(directionTo(v, x[size_t(i + 1)]), v.ng) > 0;
}

bool PathSpace::followSpecular(const MltVertex& v, const Ray& ray, bool reflect, TransportMode mode, Ray& next) const {
    if (v.kind != MltVertex::Kind::Surface || !v.bxdf || !v.delta) return false;
    const Vec3 woL = v.frame.toLocal(-ray.d);
    if (v.mixed) {
        if (!reflect) return false;
        next = spawnRay(v.p, v.ng, v.frame.toWorld(mirror(woL)), ray.time);
        return true;
    }
    for (float uc : {0.0f, 0x1.fffffep-1f}) {
        auto s = v.bxdf->sample(woL, uc, Vec2(0.5f, 0.5f), mode);
        if (s && s->isSpecular() && s->isReflection() == reflect) {
            next = spawnRay(v.p, v.ng, v.frame.toWorld(s->wi), ray.time);
            return true;
        }
    }
    return false;
}

void PathSpace::rebind(MltVertex& v, ScratchBuffer& arena) {
    if (v.kind != MltVertex::Kind::Surface) return;
    SurfaceInteraction si = v.si;
    v.bxdf = bxdfAt(si, v.lambda, arena, &v.dispersive);
}

void PathSpace::copyAt(const MltPath& x, const SampledWavelengths& lambda, ScratchBuffer& arena, MltPath& y) {
    arena.reset();
    y = x;
    for (MltVertex& v : y) {
        v.lambda = lambda;
        rebind(v, arena);
    }
}

bool PathSpace::trace(Ray ray, const SampledWavelengths& lambda, ScratchBuffer& arena, PathStats& stats, MltVertex& out,
                      bool escape, const Medium* medium, Rng* flights, MltVertex* lens) const {
    // The lens is crossed if the ray reaches it before tMax (Camera::intersectLens: from its
    // front, where its importance is not zero).
    auto crossLens = [&](float tMax) {
        if (!lens || !lensReachable_) return;
        if (const auto c = scene_.camera().intersectLens(ray, tMax)) *lens = lensVertex(c->p, ray.time, lambda);
    };
    for (int passThroughs = 0; passThroughs <= 1024; ++passThroughs) {
        SurfaceInteraction si;
        ++stats.rays;
        const bool hit = scene_.intersect(ray, si);
        const float tHit = hit ? si.t : std::numeric_limits<float>::infinity();
        if (medium && flights && traceInMedium(ray, tHit, *medium, lambda, *flights, out)) {
            crossLens(length(out.p - ray.o) / length(ray.d));  // before the flight's collision
            return true;
        }
        crossLens(tHit);
        if (!hit) {
            if (!escape || scene_.infiniteLights().empty()) return false;
            // The vertex at infinity of every infinite light (path_space.h): any of them names it.
            out = MltVertex();
            out.kind = MltVertex::Kind::Light;
            out.light = scene_.infiniteLights()[0];
            out.p = ray.o;
            out.ng = out.ns = -ray.d;
            out.time = ray.time;
            out.lambda = lambda;
            return true;
        }
        out = MltVertex();
        out.si = si;
        const BxDF* bxdf = bxdfAt(si, lambda, arena, &out.dispersive);
        if (!bxdf) {
            // `interface`: not a vertex; the ray continues (in the medium on its other side).
            medium = si.mediumToward(ray.d, medium);
            ray = spawnRay(si.p, si.ng, ray.d, ray.time);
            continue;
        }
        out.mediumAbove = si.mediumTransition ? si.mediumOutside : medium;
        out.mediumBelow = si.mediumTransition ? si.mediumInside : medium;
        out.kind = MltVertex::Kind::Surface;
        out.p = si.p;
        out.ng = si.ng;
        out.ns = si.ns;
        out.uv = si.uv;
        out.frame = si.shadingFrame();
        out.bxdf = bxdf;
        if (bxdf->stochastic()) {
            if (bxdf->specularThroughCoating()) {
                unsupportedSurface_.store(true, std::memory_order_relaxed);
                return false;
            }
            out.mixed = true;
        } else {
            out.delta = (bxdf->flags() & (kDiffuse | kGlossy)) == 0;
        }
        out.light = si.areaLight;
        out.time = ray.time;
        out.lambda = lambda;
        return true;
    }
    return false;
}

float PathSpace::drawTime(Rng& rng, const float* given) const {
    const Camera& camera = scene_.camera();
    if (!scene_.hasMotion()) return camera.shutterTime(0);
    const float u = rng.uniform();
    return camera.shutterTime(given ? *given : u);
}

SampledWavelengths PathSpace::drawWavelengths(Rng& rng, const float* given) const {
    if (!sensor_) return SampledWavelengths();
    const float u = rng.uniform();
    return SpectralFilm::sampleWavelengths(given ? *given : u);
}

SampledWavelengths PathSpace::perturbWavelengths(const SampledWavelengths& lambda, Rng& rng) const {
    if (!sensor_) return lambda;
    constexpr double r1 = 1e-3, r2 = 0.25;
    const double r = r1 * std::pow(r2 / r1, rng.uniformDouble());
    double u = double(lambda.u) + (rng.uniform() < 0.5f ? -r : r);
    u -= std::floor(u);
    return SpectralFilm::sampleWavelengths(std::fmin(float(u), 0x1.fffffep-1f));
}

bool PathSpace::walk(std::vector<MltVertex>& side, int count, TransportMode mode, float time,
                     const SampledWavelengths& lambda, Rng& rng, ScratchBuffer& arena, PathStats& stats,
                     const WalkStart* start, std::vector<MltLensHit>* lensHits) const {
    if (count <= 0) return true;
    if (!canContinue(int(side.size()), mode)) return false;
    Ray ray;
    if (mode == TransportMode::Importance && side.empty()) {
        // A light chosen as light subpaths choose (Scene::sampleLight), a point and a direction on it.
        ++stats.lightPaths;
        float uLight = rng.uniform();
        Vec2 uPos(rng.uniform(), rng.uniform()), uDir(rng.uniform(), rng.uniform());
        if (start) uLight = start->choice, uPos = start->point, uDir = start->direction;
        float pmf;
        const Light* light = scene_.sampleLight(uLight, &pmf);
        if (!light || !(pmf > 0)) return false;
        auto les = light->sampleLe(uPos, uDir, nullptr);
        if (!les || !(les->pdfPos > 0) || !(les->pdfDir > 0)) return false;
        MltVertex v;
        v.kind = MltVertex::Kind::Light;
        v.light = light;
        v.delta = light->isDelta();
        v.p = les->ray.o;
        v.ng = v.ns = les->n;
        v.uv = les->uv;
        v.time = time;
        v.lambda = lambda;
        ray = spawnRay(v.p, v.ng, les->ray.d, time);
        if (light->atInfinity()) {
            // A direction (path_space.h); the ray starts on the disk at infinity.
            v.ng = v.ns = les->ray.d;
            ray = les->ray;
            ray.time = time;
        }
        side.push_back(v);
        --count;
    } else if (mode == TransportMode::Radiance && side.size() <= 1) {
        // A film point uniform over the film widened by the filter radius (where the
        // camera's importance and its direction density live) and a lens point; a kept
        // pinhole is the same point.
        ++stats.cameraPaths;
        Vec2 pFilm(-margin_.x + rng.uniform() * filmSize_.x, -margin_.y + rng.uniform() * filmSize_.y);
        Vec2 uLens(rng.uniform(), rng.uniform());
        if (start && side.empty()) {
            pFilm = Vec2(-margin_.x + start->point.x * filmSize_.x, -margin_.y + start->point.y * filmSize_.y);
            uLens = start->direction;
        }
        MltVertex lens;
        ray = cameraRay(pFilm, uLens, time, lambda, &lens);
        if (side.empty()) {
            side.push_back(lens);
            --count;
        }
    } else if (!scatter(side, mode, rng, ray)) {
        return false;
    } else {
        start = nullptr;  // a side that had vertices: none of the walk's numbers is a start's
    }
    while (count > 0) {
        MltVertex next;
        // Lens crossings from a scattering vertex alone: a light seen directly through the
        // lens is the camera side's (lightDensity).
        MltLensHit hit{int(side.size()), MltVertex()};
        const bool record = lensHits && mode == TransportMode::Importance && side.size() >= 2;
        // A camera walk may end at infinity (scatter cannot continue from there).
        const bool traced = trace(ray, lambda, arena, stats, next, mode == TransportMode::Radiance,
                                  mediumFrom(side.back(), ray.d), &rng, record ? &hit.lens : nullptr);
        if (hit.lens.kind == MltVertex::Kind::Lens) lensHits->push_back(hit);
        if (!traced) return false;
        side.push_back(next);
        if (--count > 0 && !scatter(side, mode, rng, ray, start)) return false;
        start = nullptr;  // the first scattering's alone
    }
    return true;
}

Ray PathSpace::cameraRay(Vec2 pFilm, Vec2 uLens, float time, const SampledWavelengths& lambda, MltVertex* lens) const {
    CameraSample cs;
    cs.pFilm = pFilm;
    cs.pLens = pinhole_ ? Vec2(0.5f, 0.5f) : uLens;
    const Ray ray = scene_.camera().generateRayAt(cs, time);
    *lens = lensVertex(ray.o, time, lambda);
    return ray;
}

MltVertex PathSpace::lensVertex(Vec3 p, float time, const SampledWavelengths& lambda) const {
    MltVertex lens;
    lens.kind = MltVertex::Kind::Lens;
    lens.p = p;
    lens.time = time;
    lens.lambda = lambda;
    lens.ng = scene_.camera().forward(time);
    return lens;
}

bool PathSpace::reachLens(std::vector<MltVertex>& side, Rng& rng, ScratchBuffer& arena, PathStats& stats) const {
    Ray ray;
    if (!lensReachable_ || side.size() < 2 || !scatter(side, TransportMode::Importance, rng, ray)) return false;
    MltVertex next, lens;
    trace(ray, side.back().lambda, arena, stats, next, false, mediumFrom(side.back(), ray.d), &rng, &lens);
    if (lens.kind != MltVertex::Kind::Lens) return false;
    side.push_back(lens);
    return true;
}

bool PathSpace::scatter(std::vector<MltVertex>& side, TransportMode mode, Rng& rng, Ray& ray,
                        const WalkStart* start) const {
    MltVertex& v = side.back();
    if (side.size() >= 2 && v.isMedium()) return scatterInMedium(side, rng, ray);
    if (side.size() < 2 || v.kind != MltVertex::Kind::Surface || !v.bxdf) return false;
    const Vec3 woL = v.frame.toLocal(unitTo(v, side[side.size() - 2]));
    float uc = rng.uniform();
    Vec2 u(rng.uniform(), rng.uniform());
    if (start) uc = start->lobe, u = start->scatter;
    if (v.mixed) {
        // The coating's mirror with probability R(wo), else a cosine lobe on wo's side.
        v.delta = uc < v.bxdf->coatingMirrorReflectance(woL);
        Vec3 wiL = sampleCosineHemisphere(u);
        if (v.delta) wiL = mirror(woL);
        else if (woL.z < 0) wiL.z = -wiL.z;
        if (wiL.z == 0) return false;
        ray = spawnRay(v.p, v.ng, v.frame.toWorld(wiL), v.time);
        return true;
    }
    auto bs = v.bxdf->sample(woL, uc, u, mode);
    if (!bs || !(bs->pdf > 0) || bs->f.isBlack()) return false;
    ray = spawnRay(v.p, v.ng, v.frame.toWorld(bs->wi), v.time);
    return true;
}

double PathSpace::infinityDensity(const MltVertex& v) const {
    if (v.delta) return double(scene_.lightPmf(v.light));
    double pdf = 0;
    for (const Light* light : scene_.infiniteLights()) {
        float pdfPos, pdfDir;
        light->pdfLe(Vec3(), Vec3(), v.ng, &pdfPos, &pdfDir);
        pdf += double(scene_.lightPmf(light)) * pdfDir;
    }
    return pdf;
}

Spectrum PathSpace::emitted(const MltVertex& x0, const MltVertex& x1) const {
    const SampledWavelengths* lambda = wavelengthsOf(x0);
    if (!atInfinity(x0)) return x0.light->L(x0.p, x0.ng, x0.uv, unitTo(x0, x1), lambda);
    if (x0.delta) {
        // A distant light: its radiance along its own direction (a delta of unit weight).
        auto li = x0.light->sampleLi(LightSampleContext{x1.p, x1.ng, lambda}, Vec2(0.5f, 0.5f));
        return li && dot(li->wi, x0.ng) < -0.9999f ? li->L : Spectrum();
    }
    Spectrum L;
    for (const Light* light : scene_.infiniteLights()) L += light->Le(Ray{x1.p, -x0.ng}, lambda);
    return L;
}

}  // namespace ps
