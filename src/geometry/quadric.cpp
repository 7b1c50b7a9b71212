#include "geometry/quadric.h"

#include "materials/material.h"
#include "math/warp.h"

namespace ps {

namespace {

void boundsCallback(const RTCBoundsFunctionArguments* args) {
    auto* q = static_cast<const Quadric*>(args->geometryUserPtr);
    Bounds3 sb = q->primitiveBounds(0);
    Vec3 blo = sb.lo, bhi = sb.hi;
    RTCBounds* b = args->bounds_o;
    b->lower_x = blo.x; b->lower_y = blo.y; b->lower_z = blo.z;
    b->upper_x = bhi.x; b->upper_y = bhi.y; b->upper_z = bhi.z;
}

// Only single rays are traced (rtcIntersect1 / rtcOccluded1), so N is 1.
void intersectCallback(const RTCIntersectFunctionNArguments* args) {
    if (!args->valid[0]) return;
    auto* q = static_cast<const Quadric*>(args->geometryUserPtr);
    RTCRayHit* rh = reinterpret_cast<RTCRayHit*>(args->rayhit);
    const Transform inv = q->toScene().inverse();
    Ray r{{rh->ray.org_x, rh->ray.org_y, rh->ray.org_z}, {rh->ray.dir_x, rh->ray.dir_y, rh->ray.dir_z}};
    float t = q->nearestKeptHit(r, inv.point(r.o), inv.vector(r.d), rh->ray.tfar);
    if (t > rh->ray.tnear && t < rh->ray.tfar) {
        rh->ray.tfar = t;
        rh->hit.u = rh->hit.v = 0;
        rh->hit.Ng_x = rh->hit.Ng_y = 0;
        rh->hit.Ng_z = 1;
        rh->hit.primID = args->primID;
        rh->hit.geomID = args->geomID;
        rh->hit.instID[0] = args->context->instID[0];
    }
}

void occludedCallback(const RTCOccludedFunctionNArguments* args) {
    if (!args->valid[0]) return;
    auto* q = static_cast<const Quadric*>(args->geometryUserPtr);
    RTCRay* ray = reinterpret_cast<RTCRay*>(args->ray);
    const Transform inv = q->toScene().inverse();
    Ray r{{ray->org_x, ray->org_y, ray->org_z}, {ray->dir_x, ray->dir_y, ray->dir_z}};
    float t = q->nearestKeptHit(r, inv.point(r.o), inv.vector(r.d), ray->tfar);
    if (t > ray->tnear && t < ray->tfar) ray->tfar = -std::numeric_limits<float>::infinity();
}

// The roots t0 <= t1 of a t^2 + b t + c = 0 (double precision, the cancellation-free form);
// false when there are none (or a = 0).
bool solveQuadratic(double a, double b, double c, double& t0, double& t1) {
    double disc = b * b - 4 * a * c;
    if (disc < 0 || a == 0) return false;
    double root = std::sqrt(disc);
    double q = b < 0 ? -0.5 * (b - root) : -0.5 * (b + root);
    t0 = q / a;
    t1 = c / q;
    if (t0 > t1) std::swap(t0, t1);
    return true;
}

float phiOf(Vec3 p) {
    float phi = std::atan2(p.y, p.x);
    return phi < 0 ? phi + 2 * kPi : phi;
}

// dn/du and dn/dv of the unit normal normalize(dpdu x dpdv) from the second derivatives of
// p (Weingarten equations), as pbrt-v4's quadrics compute them.
void weingarten(Vec3 dpdu, Vec3 dpdv, Vec3 d2pduu, Vec3 d2pduv, Vec3 d2pdvv, Vec3& dndu, Vec3& dndv) {
    float E = dot(dpdu, dpdu), F = dot(dpdu, dpdv), G = dot(dpdv, dpdv);
    Vec3 n = normalize(cross(dpdu, dpdv));
    float e = dot(n, d2pduu), f = dot(n, d2pduv), g = dot(n, d2pdvv);
    float egf2 = E * G - F * F;
    float inv = egf2 == 0 ? 0.0f : 1 / egf2;
    dndu = dpdu * ((f * F - e * G) * inv) + dpdv * ((e * F - f * E) * inv);
    dndv = dpdu * ((g * F - f * G) * inv) + dpdv * ((f * F - g * E) * inv);
}

}  // namespace

bool Quadric::wantsDerivatives() const { return material && material->needsShadingDerivatives(); }

// The normal's derivatives are not flipped with the normal (pbrt-v4 flips n only).
void Quadric::setDerivatives(SurfaceInteraction& si, Vec3 dpdu, Vec3 dpdv, Vec3 dndu, Vec3 dndv) const {
    si.dpdu = toScene_.vector(dpdu);
    si.dpdv = toScene_.vector(dpdv);
    si.dndu = toScene_.normal(dndu);
    si.dndv = toScene_.normal(dndv);
    si.tangentIsFrameAxis = false;
}

// User geometry gets no Embree filter calls, so the alpha test runs here, on each surface
// crossing in turn, for closest hits and occlusion alike.
float Quadric::nearestKeptHit(const Ray& sceneRay, Vec3 o, Vec3 d, float tMax) const {
    float t = intersectObject(o, d, 0, tMax);
    while (alpha && t > 0 && !keepsHit(sceneRay, t, 0, 0, 0)) t = intersectObject(o, d, t, tMax);
    return t;
}

RTCGeometry Quadric::buildGeometry(RTCDevice device) const {
    RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
    rtcSetGeometryUserPrimitiveCount(g, 1);
    rtcSetGeometryUserData(g, const_cast<Quadric*>(this));
    rtcSetGeometryBoundsFunction(g, boundsCallback, nullptr);
    rtcSetGeometryIntersectFunction(g, intersectCallback);
    rtcSetGeometryOccludedFunction(g, occludedCallback);
    rtcCommitGeometry(g);
    return g;
}

// ---- Sphere ----

Sphere::Sphere(const Transform& toScene, bool reverseOrientation, float radius, float zMin, float zMax, float phiMaxDeg)
    : Quadric(toScene, reverseOrientation), radius_(radius) {
    zMin_ = clampf(std::min(zMin, zMax), -radius, radius);
    zMax_ = clampf(std::max(zMin, zMax), -radius, radius);
    thetaZMin_ = std::acos(clampf(zMin_ / radius, -1, 1));
    thetaZMax_ = std::acos(clampf(zMax_ / radius, -1, 1));
    phiMax_ = radians(clampf(phiMaxDeg, 0, 360));
    full_ = zMin_ <= -radius && zMax_ >= radius && phiMaxDeg >= 360;
    center_ = toScene.point({0, 0, 0});
    sceneRadius_ = radius * length(toScene.vector({1, 0, 0}));
}

Bounds3 Quadric::primitiveBounds(int) const {
    Vec3 lo, hi;
    objectBounds(lo, hi);
    Bounds3 b;
    for (int i = 0; i < 8; ++i)
        b.expand(toScene_.point(Vec3((i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z)));
    return b;
}

void Sphere::objectBounds(Vec3& lo, Vec3& hi) const {
    lo = {-radius_, -radius_, zMin_};
    hi = {radius_, radius_, zMax_};
}

bool Sphere::inRange(Vec3 p) const {
    if (full_) return true;
    if (p.z < zMin_ || p.z > zMax_) return false;
    return phiOf(p) <= phiMax_;
}

float Sphere::intersectObject(Vec3 o, Vec3 d, float tMin, float tMax) const {
    // Quadratic in double precision: |o + t d|^2 = r^2.
    double a = double(d.x) * d.x + double(d.y) * d.y + double(d.z) * d.z;
    double b = 2 * (double(d.x) * o.x + double(d.y) * o.y + double(d.z) * o.z);
    double c = double(o.x) * o.x + double(o.y) * o.y + double(o.z) * o.z - double(radius_) * radius_;
    double t0, t1;
    if (!solveQuadratic(a, b, c, t0, t1)) return -1;
    for (double td : {t0, t1}) {
        const float t = float(td);  // compared as returned: a cut-out hit's t is the next tMin
        if (!(t > tMin) || t >= tMax) continue;
        Vec3 p = o + d * t;
        if (inRange(p)) return t;
    }
    return -1;
}

int Sphere::interaction(const Ray& r, float t, int, float, float, SurfaceInteraction& si) const {
    Vec3 pObj = toScene_.inverse().point(r.o + r.d * t);
    float l = length(pObj);
    if (l > 0) pObj = pObj * (radius_ / l);  // reproject onto the surface
    float phi = phiOf(pObj);
    float theta = safeAcos(pObj.z / radius_);
    si.uv = {phi / phiMax_, (theta - thetaZMin_) / (thetaZMax_ - thetaZMin_)};
    si.p = toScene_.point(pObj);
    si.t = t;
    Vec3 n = normalize(toScene_.normal(pObj));
    if (flip_) n = -n;
    si.ng = si.ns = n;
    si.dpdu = toScene_.vector({-phiMax_ * pObj.y, phiMax_ * pObj.x, 0});
    if (wantsDerivatives()) {
        Vec3 q = pObj;
        if (q.x == 0 && q.y == 0) q.x = 1e-5f * radius_;  // on the axis phi is undefined: as pbrt-v4
        float zRadius = std::sqrt(q.x * q.x + q.y * q.y);
        float cosPhi = q.x / zRadius, sinPhi = q.y / zRadius;
        float sinTheta = safeSqrt(1 - sqr(q.z / radius_));
        float dTheta = thetaZMax_ - thetaZMin_;
        Vec3 dpdu(-phiMax_ * q.y, phiMax_ * q.x, 0);
        Vec3 dpdv = Vec3(q.z * cosPhi, q.z * sinPhi, -radius_ * sinTheta) * dTheta;
        Vec3 d2pduu = Vec3(q.x, q.y, 0) * (-phiMax_ * phiMax_);
        Vec3 d2pduv = Vec3(-sinPhi, cosPhi, 0) * (dTheta * q.z * phiMax_);
        Vec3 d2pdvv = q * (-dTheta * dTheta);
        Vec3 dndu, dndv;
        weingarten(dpdu, dpdv, d2pduu, d2pduv, d2pdvv, dndu, dndv);
        setDerivatives(si, dpdu, dpdv, dndu, dndv);
    }
    return 0;
}

float Sphere::area(int) const {
    float s = sceneRadius_ / radius_;
    return phiMax_ * radius_ * (zMax_ - zMin_) * s * s;
}

// Uniform over the whole sphere; points outside a partial sphere get pdf 0 (rejected).
ShapeSample Sphere::sampleArea(int, Vec2 u) const {
    Vec3 pObj = sampleUniformSphere(u) * radius_;
    ShapeSample s;
    s.p = toScene_.point(pObj);
    Vec3 n = normalize(toScene_.normal(pObj));
    s.n = flip_ ? -n : n;
    float phi = phiOf(pObj);
    s.uv = {phi / phiMax_, (safeAcos(pObj.z / radius_) - thetaZMin_) / (thetaZMax_ - thetaZMin_)};
    s.pdf = inRange(pObj) ? 1.0f / (4 * kPi * sceneRadius_ * sceneRadius_) : 0.0f;
    return s;
}

// Outside a full sphere: sample the cone of directions it subtends (uniform in solid angle).
std::optional<ShapeSample> Sphere::sampleToward(int prim, Vec3 ref, Vec2 u) const {
    Vec3 toC = center_ - ref;
    float dc2 = lengthSquared(toC);
    float r2 = sceneRadius_ * sceneRadius_;
    if (!full_ || dc2 <= r2 * 1.0001f) return Shape::sampleToward(prim, ref, u);
    float dc = std::sqrt(dc2);
    float sin2Max = r2 / dc2;
    float cosMax = safeSqrt(1 - sin2Max);
    float oneMinusCosMax = sin2Max / (1 + cosMax);  // stable for tiny cones
    float omc = u.x * oneMinusCosMax;
    float cosT = 1 - omc;
    float sin2T = omc * (2 - omc);
    float sinT = safeSqrt(sin2T);
    float phi = 2 * kPi * u.y;
    Frame f = Frame::fromNormal(toC / dc);
    Vec3 w = f.toWorld({sinT * std::cos(phi), sinT * std::sin(phi), cosT});
    // Nearest intersection along w. The squared distance of the ray from the centre is
    // dc2 sin^2(theta), not dc2 - b^2: that difference of two large numbers lost the
    // discriminant near the silhouette of a small, distant sphere, and the point then fell
    // inside the sphere, which blocked the shadow ray to it.
    float disc = r2 - dc2 * sin2T;
    float t = dc * cosT - safeSqrt(disc);
    ShapeSample s;
    s.p = ref + w * t;
    s.wi = w;
    Vec3 n = normalize(s.p - center_);
    s.n = flip_ ? -n : n;
    Vec3 pObj = toScene_.inverse().point(s.p);
    s.uv = {phiOf(pObj) / phiMax_, (safeAcos(pObj.z / radius_) - thetaZMin_) / (thetaZMax_ - thetaZMin_)};
    s.pdf = 1 / (2 * kPi * oneMinusCosMax);
    s.pdfArea = pdfArea(prim);
    if (!std::isfinite(s.pdf)) return std::nullopt;
    return s;
}

float Sphere::pdfToward(int prim, Vec3 ref, Vec3 hitP, Vec3 hitN) const {
    Vec3 toC = center_ - ref;
    float dc2 = lengthSquared(toC);
    float r2 = sceneRadius_ * sceneRadius_;
    if (!full_ || dc2 <= r2 * 1.0001f) {
        Vec3 d = hitP - ref;
        float dist2 = lengthSquared(d);
        if (!(dist2 > 0)) return 0;
        float pdf = areaToSolidAngle(1 / (4 * kPi * r2), dist2, absDot(hitN, d) / std::sqrt(dist2));
        return std::isfinite(pdf) ? pdf : 0.0f;
    }
    (void)prim;
    float sin2Max = r2 / dc2;
    float cosMax = safeSqrt(1 - sin2Max);
    return 1 / (2 * kPi * (sin2Max / (1 + cosMax)));
}

// ---- Disk ----

Disk::Disk(const Transform& toScene, bool reverseOrientation, float height, float radius, float innerRadius, float phiMaxDeg)
    : Quadric(toScene, reverseOrientation), height_(height), radius_(radius),
      innerRadius_(clampf(innerRadius, 0, radius)), phiMax_(radians(clampf(phiMaxDeg, 0, 360))) {}

void Disk::objectBounds(Vec3& lo, Vec3& hi) const {
    lo = {-radius_, -radius_, height_};
    hi = {radius_, radius_, height_};
}

float Disk::intersectObject(Vec3 o, Vec3 d, float tMin, float tMax) const {
    if (d.z == 0) return -1;
    float t = (height_ - o.z) / d.z;
    if (!(t > tMin) || t >= tMax) return -1;
    Vec3 p = o + d * t;
    float rho2 = p.x * p.x + p.y * p.y;
    if (rho2 > radius_ * radius_ || rho2 < innerRadius_ * innerRadius_) return -1;
    if (phiMax_ < 2 * kPi && phiOf(p) > phiMax_) return -1;
    return t;
}

int Disk::interaction(const Ray& r, float t, int, float, float, SurfaceInteraction& si) const {
    Vec3 pObj = toScene_.inverse().point(r.o + r.d * t);
    pObj.z = height_;
    float rho = std::sqrt(pObj.x * pObj.x + pObj.y * pObj.y);
    float denom = radius_ - innerRadius_;
    si.uv = {phiOf(pObj) / phiMax_, denom > 0 ? (radius_ - rho) / denom : 0.0f};
    si.p = toScene_.point(pObj);
    si.t = t;
    Vec3 n = normalize(toScene_.normal({0, 0, 1}));
    if (flip_) n = -n;
    si.ng = si.ns = n;
    si.dpdu = toScene_.vector({-phiMax_ * pObj.y, phiMax_ * pObj.x, 0});
    if (wantsDerivatives() && rho > 0) {
        Vec3 dpdv = Vec3(pObj.x, pObj.y, 0) * ((innerRadius_ - radius_) / rho);
        setDerivatives(si, {-phiMax_ * pObj.y, phiMax_ * pObj.x, 0}, dpdv, {}, {});
    }
    return 0;
}

DirectionCone Disk::normalBounds(int) const {
    Vec3 n = normalize(toScene_.normal({0, 0, 1}));
    return DirectionCone(flip_ ? -n : n, 1);
}

float Disk::area(int) const {
    float sx = length(toScene_.vector({1, 0, 0})), sy = length(toScene_.vector({0, 1, 0}));
    return 0.5f * phiMax_ * (radius_ * radius_ - innerRadius_ * innerRadius_) * sx * sy;
}

ShapeSample Disk::sampleArea(int, Vec2 u) const {
    // Uniform on the annulus sector: r^2 uniform between inner^2 and outer^2.
    float r = std::sqrt(lerp(u.x, innerRadius_ * innerRadius_, radius_ * radius_));
    float phi = u.y * phiMax_;
    Vec3 pObj(r * std::cos(phi), r * std::sin(phi), height_);
    ShapeSample s;
    s.p = toScene_.point(pObj);
    Vec3 n = normalize(toScene_.normal({0, 0, 1}));
    s.n = flip_ ? -n : n;
    float denom = radius_ - innerRadius_;
    s.uv = {phi / phiMax_, denom > 0 ? (radius_ - r) / denom : 0.0f};
    float a = area(0);
    s.pdf = a > 0 ? 1 / a : 0;
    return s;
}

// ---- Cylinder ----

Cylinder::Cylinder(const Transform& toScene, bool reverseOrientation, float radius, float zMin, float zMax, float phiMaxDeg)
    : Quadric(toScene, reverseOrientation), radius_(radius), zMin_(std::min(zMin, zMax)), zMax_(std::max(zMin, zMax)),
      phiMax_(radians(clampf(phiMaxDeg, 0, 360))) {}

void Cylinder::objectBounds(Vec3& lo, Vec3& hi) const {
    lo = {-radius_, -radius_, zMin_};
    hi = {radius_, radius_, zMax_};
}

float Cylinder::intersectObject(Vec3 o, Vec3 d, float tMin, float tMax) const {
    // Quadratic in double precision: (o + t d).xy^2 = r^2.
    double a = double(d.x) * d.x + double(d.y) * d.y;
    double b = 2 * (double(d.x) * o.x + double(d.y) * o.y);
    double c = double(o.x) * o.x + double(o.y) * o.y - double(radius_) * radius_;
    double t0, t1;
    if (!solveQuadratic(a, b, c, t0, t1)) return -1;  // a == 0: parallel to the axis, never on the wall
    for (double td : {t0, t1}) {
        const float t = float(td);  // compared as returned (see Sphere::intersectObject)
        if (!(t > tMin) || t >= tMax) continue;
        Vec3 p = o + d * t;
        if (p.z < zMin_ || p.z > zMax_) continue;
        if (phiMax_ < 2 * kPi && phiOf(p) > phiMax_) continue;
        return t;
    }
    return -1;
}

Vec3 Cylinder::normalAt(Vec3 pObj) const {
    Vec3 n = normalize(toScene_.normal({pObj.x, pObj.y, 0}));
    return flip_ ? -n : n;
}

int Cylinder::interaction(const Ray& r, float t, int, float, float, SurfaceInteraction& si) const {
    Vec3 pObj = toScene_.inverse().point(r.o + r.d * t);
    float rho = std::sqrt(pObj.x * pObj.x + pObj.y * pObj.y);
    if (rho > 0) {  // reproject onto the wall
        pObj.x *= radius_ / rho;
        pObj.y *= radius_ / rho;
    }
    si.uv = {phiOf(pObj) / phiMax_, zMax_ > zMin_ ? (pObj.z - zMin_) / (zMax_ - zMin_) : 0.0f};
    si.p = toScene_.point(pObj);
    si.t = t;
    si.ng = si.ns = normalAt(pObj);
    si.dpdu = toScene_.vector({-phiMax_ * pObj.y, phiMax_ * pObj.x, 0});
    if (wantsDerivatives()) {
        Vec3 dpdu(-phiMax_ * pObj.y, phiMax_ * pObj.x, 0), dpdv(0, 0, zMax_ - zMin_);
        Vec3 dndu, dndv;
        weingarten(dpdu, dpdv, Vec3(pObj.x, pObj.y, 0) * (-phiMax_ * phiMax_), {}, {}, dndu, dndv);
        setDerivatives(si, dpdu, dpdv, dndu, dndv);
    }
    return 0;
}

float Cylinder::area(int) const {
    float sxy = length(toScene_.vector({1, 0, 0})), sz = length(toScene_.vector({0, 0, 1}));
    return phiMax_ * radius_ * sxy * (zMax_ - zMin_) * sz;
}

ShapeSample Cylinder::sampleArea(int, Vec2 u) const {
    float z = lerp(u.x, zMin_, zMax_), phi = u.y * phiMax_;
    Vec3 pObj(radius_ * std::cos(phi), radius_ * std::sin(phi), z);
    ShapeSample s;
    s.p = toScene_.point(pObj);
    s.n = normalAt(pObj);
    s.uv = {u.y, u.x};
    float a = area(0);
    s.pdf = a > 0 ? 1 / a : 0;
    return s;
}

}  // namespace ps
