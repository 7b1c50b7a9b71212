#include "render/scene.h"

#include <limits>

namespace ps {

Scene::Scene() = default;

Scene::~Scene() {
    if (scene_) rtcReleaseScene(scene_);
    for (RTCScene s : prototypeScenes_) rtcReleaseScene(s);
    if (device_) rtcReleaseDevice(device_);
}

static void toEmbree(const Ray& r, RTCRay& ray) {
    ray.org_x = r.o.x; ray.org_y = r.o.y; ray.org_z = r.o.z;
    ray.dir_x = r.d.x; ray.dir_y = r.d.y; ray.dir_z = r.d.z;
    ray.tnear = 0;
    ray.tfar = r.tMax;
    ray.time = 0;
    ray.mask = 0xffffffffu;
    ray.id = 0;
    ray.flags = 0;
}

bool Scene::intersect(const Ray& r, SurfaceInteraction& si) const {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRayHit rh;
    toEmbree(r, rh.ray);
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
    } else {
        // Instances: compute the hit in the prototype's space, then map it to the world.
        const Instance& inst = instances_[instanceOfGeometry_[rh.hit.instID[0]]];
        const Shape* shape = prototypeGeometry_[inst.prototype][rh.hit.geomID];
        const Transform& T = inst.worldFromPrototype;
        Transform inv = T.inverse();
        Ray local{inv.point(r.o), inv.vector(r.d), r.tMax};
        shape->interaction(local, t, int(rh.hit.primID), rh.hit.u, rh.hit.v, si);
        si.p = T.point(si.p);
        si.ng = normalize(T.normal(si.ng));
        si.ns = normalize(T.normal(si.ns));
        si.dpdu = T.vector(si.dpdu);
        si.tangentIsFrameAxis = false;  // the transform may scale it
        si.material = shape->material;
        si.areaLight = nullptr;  // emitters inside instances are not supported (as in pbrt-v4)
    }
    si.t = t;
    si.wo = -normalize(r.d);
    return true;
}

bool Scene::occluded(const Ray& r) const {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRay ray;
    toEmbree(r, ray);
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
