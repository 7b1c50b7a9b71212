#include "render/scene.h"

#include <limits>

#if defined(__SSE2__)
#include <immintrin.h>
#endif

namespace ps {

Scene::Scene() = default;

Scene::~Scene() {
    if (scene_) rtcReleaseScene(scene_);
    for (RTCScene s : prototypeScenes_) rtcReleaseScene(s);
    if (device_) rtcReleaseDevice(device_);
}

// Embree loads the ray as 16-byte vectors (origin and tnear, direction and time, ...). Written
// field by field, each such load waits for four scalar stores to reach the cache (store
// forwarding cannot combine them): measured as up to 4% of BDPT's time on Embree's first
// instruction. Whole-vector stores forward directly.
static void toEmbree(const Ray& r, float time, RTCRay& ray) {
#if defined(__SSE2__)
    _mm_store_ps(&ray.org_x, _mm_setr_ps(r.o.x, r.o.y, r.o.z, 0.0f));
    _mm_store_ps(&ray.dir_x, _mm_setr_ps(r.d.x, r.d.y, r.d.z, time));
    _mm_store_si128(reinterpret_cast<__m128i*>(&ray.tfar),
                    _mm_setr_epi32(_mm_cvtsi128_si32(_mm_castps_si128(_mm_set_ss(r.tMax))), -1, 0, 0));
#else
    ray.org_x = r.o.x; ray.org_y = r.o.y; ray.org_z = r.o.z;
    ray.dir_x = r.d.x; ray.dir_y = r.d.y; ray.dir_z = r.d.z;
    ray.tnear = 0;
    ray.tfar = r.tMax;
    ray.time = time;
    ray.mask = 0xffffffffu;
    ray.id = 0;
    ray.flags = 0;
#endif
}

bool Scene::intersect(const Ray& r, SurfaceInteraction& si) const {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRayHit rh;
    toEmbree(r, embreeTime(r.time), rh.ray);
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene_, &ctx, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;

    float t = rh.ray.tfar;
    if (rh.hit.instID[0] == RTC_INVALID_GEOMETRY_ID) {
        const Shape* shape = worldGeometry_[rh.hit.geomID];
        int prim = shape->interaction(r, t, int(rh.hit.primID), rh.hit.u, rh.hit.v, si);
        si.material = shape->material;
        si.areaLight = shape->areaLights.empty() ? nullptr : shape->areaLights[prim];
        si.mediumInside = shape->mediumInside;
        si.mediumOutside = shape->mediumOutside;
        si.mediumTransition = shape->mediumTransition;
    } else {
        // Instances: compute the hit in the prototype's space, then map it to the world.
        const Instance& inst = instances_[instanceOfGeometry_[rh.hit.instID[0]]];
        const Shape* shape = prototypeGeometry_[inst.prototype][rh.hit.geomID];
        Transform moving;
        if (inst.motion.isAnimated()) moving = inst.motion.interpolate(r.time) * inst.objectFromPrototype;
        const Transform& T = inst.motion.isAnimated() ? moving : inst.worldFromPrototype;
        Transform inv = T.inverse();
        Ray local{inv.point(r.o), inv.vector(r.d), r.tMax, r.time};
        shape->interaction(local, t, int(rh.hit.primID), rh.hit.u, rh.hit.v, si);
        si.p = T.point(si.p);
        si.ng = normalize(T.normal(si.ng));
        si.ns = normalize(T.normal(si.ns));
        si.dpdu = T.vector(si.dpdu);
        si.tangentIsFrameAxis = false;  // the transform may scale it
        if (shape->material && shape->material->needsShadingDerivatives()) {
            si.dpdv = T.vector(si.dpdv);
            si.dndu = T.normal(si.dndu);
            si.dndv = T.normal(si.dndv);
        }
        si.material = shape->material;
        si.areaLight = nullptr;  // emitters inside instances are not supported (as in pbrt-v4)
        si.mediumInside = shape->mediumInside;
        si.mediumOutside = shape->mediumOutside;
        si.mediumTransition = shape->mediumTransition;
    }
    si.t = t;
    si.wo = -normalize(r.d);
    return true;
}

bool Scene::occluded(const Ray& r) const {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRay ray;
    toEmbree(r, embreeTime(r.time), ray);
    rtcOccluded1(scene_, &ctx, &ray);
    return ray.tfar < 0;
}

const Light* Scene::sampleLight(float u, float* pmf) const {
    if (lights_.empty()) {
        *pmf = 0;
        return nullptr;
    }
    int i = lightDistribution_.sample(u);
    *pmf = lightDistribution_.pmf(i);
    return lights_[size_t(i)].get();
}

float Scene::lightPmf(const Light* light) const {
    if (!light || light->index < 0) return 0;
    return lightDistribution_.pmf(light->index);
}

}  // namespace ps
