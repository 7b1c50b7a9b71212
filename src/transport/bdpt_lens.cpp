// BDPT's t = 0 strategy (thesis §10.2): a light subpath that reaches a thin lens by itself.
// Its path x_0 .. x_{k-1} is the light subpath's and x_k is the lens point the ray crossed;
// the estimate is beta W_e (the walk's throughput arriving there, which holds the geometry
// term's share against the area density of the lens point), and it is weighted against the
// strategies that sample the same vertices from the camera side, where the camera's density
// of the lens point is 1 / (lens area). With a delta light and a specular vertex next to the
// lens it is the only strategy of the path (thesis §1.1); a pinhole is never hit.
#include "transport/bdpt.h"

namespace ps {

void BDPTIntegrator::disableLensHits() {
    lensHits_ = false;
    paths_.setLensHits(false);
}

float BDPTIntegrator::lensRatio(float rev, const PathVertex& lens, const PathVertex& next) const {
    if (!lensHits_ || !(rev > 0)) return 0;
    const Camera& camera = paths_.scene().camera();
    const Vec3 d = next.p - lens.p;
    const float d2 = lengthSquared(d);
    if (!(d2 > 0)) return 0;
    const float cosLens = std::fabs(dot(camera.forward(lens.time), d)) / std::sqrt(d2);
    return rev * cosLens / camera.lensPdfArea();
}

BDPTIntegrator::Connection BDPTIntegrator::connectLens(const PathVertex* light, const LensHit& hit,
                                                       ScratchBuffer& scratch, const MisPrefixes* prefixes) const {
    Connection c;
    const int s = hit.index + 1;
    auto* path = static_cast<PathVertex*>(scratch.allocBytes(sizeof(PathVertex) * size_t(s), alignof(PathVertex)));
    for (int i = 0; i < hit.index; ++i) path[i] = light[i];
    PathVertex& lens = path[hit.index];
    resetVertex(lens);
    lens.kind = VertexKind::Camera;
    lens.mode = TransportMode::Radiance;
    lens.p = hit.lens.p;
    lens.time = light[hit.index - 1].time;
    lens.beta = Spectrum(hit.lens.We);
    // The walk's area density at the lens (thesis eq. 8.10, with the lens cosine).
    const float d2 = lengthSquared(lens.p - path[hit.index - 1].p);
    if (!(d2 > 0)) return c;
    lens.pdfFwd = hit.pdfDir * hit.lens.cosLens / d2;
    c.L = hit.beta * hit.lens.We;
    if (c.L.isBlack()) return c;
    if (!c.L.isFinite()) {
        c.L = Spectrum();
        return c;
    }
    c.pRaster = hit.lens.pRaster;
    c.weight = misWeight(path, nullptr, nullptr, s, 0, nullptr, prefixes);
    if (recomputeWeights_) c.recomputedWeight = misWeight(path, nullptr, nullptr, s, 0, nullptr);
    return c;
}

}  // namespace ps
