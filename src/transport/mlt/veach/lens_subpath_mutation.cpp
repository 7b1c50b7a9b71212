#include "transport/mlt/veach/lens_subpath_mutation.h"

namespace ps {

namespace {

bool isD(const MltVertex& v) { return v.kind == MltVertex::Kind::Surface && v.bxdf && !v.delta; }
bool isS(const MltVertex& v) { return v.kind == MltVertex::Kind::Surface && v.bxdf && v.delta; }

}  // namespace

int LensSubpathMutation::subpathStart(const MltPath& x) const {
    const int k = int(x.size()) - 1;
    int m = k - 1;
    while (m > 0 && isS(x[size_t(m)])) --m;
    if (m == 0) return x[0].light && !x[0].delta ? 0 : -1;  // the new subpath must be able to hit the light
    return isD(x[size_t(m)]) && space_.connectible(x, m - 1) ? m : -1;
}

bool LensSubpathMutation::applies(const MltPath& x) const { return subpathStart(x) >= 0; }

double LensSubpathMutation::subpathDensity(const MltPath& z, int start) const {
    double p = 1;
    for (int i = int(z.size()) - 1; i >= start && p > 0; --i) p *= space_.cameraDensity(z, i);
    return p;
}

bool LensSubpathMutation::propose(const MltPath& x, Rng& rng, ScratchBuffer& arena, PathStats& stats,
                                  MltPath& y, double* ratio) const {
    const int m = subpathStart(x);
    if (m < 0) return false;
    arena.reset();
    // The new subpath, from the lens.
    std::vector<MltVertex> camera(1);
    const Vec2 u(rng.uniform(), rng.uniform());
    const Vec2 pFilm(-space_.filmMargin().x + u.x * space_.filmSize().x,
                     -space_.filmMargin().y + u.y * space_.filmSize().y);
    Ray ray = space_.cameraRay(pFilm, Vec2(rng.uniform(), rng.uniform()), &camera[0]);
    ++stats.cameraPaths;
    while (true) {
        if (m + int(camera.size()) >= space_.maxVertices()) return false;
        MltVertex v;
        if (!space_.trace(ray, arena, stats, v)) return false;
        camera.push_back(v);
        if (m == 0 ? v.light != nullptr : !v.delta) break;  // the subpath's end
        if (!isS(v) || !space_.scatter(camera, TransportMode::Radiance, rng, ray)) return false;
    }
    if (m > 0 && !isD(camera.back())) return false;
    y.assign(x.begin(), x.begin() + m);
    for (MltVertex& v : y) PathSpace::rebind(v, arena);
    y.insert(y.end(), camera.rbegin(), camera.rend());
    if (m > 0 && !space_.visible(y[size_t(m - 1)], y[size_t(m)], stats)) return false;
    const double py = subpathDensity(y, m);
    if (!(py > 0)) return false;
    *ratio = subpathDensity(x, m) / py;
    return true;
}

}  // namespace ps
