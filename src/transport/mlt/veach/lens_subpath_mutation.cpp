#include "transport/mlt/veach/lens_subpath_mutation.h"

namespace ps {

int LensSubpathMutation::subpathStart(const MltPath& x) const {
    const int m = space_.specularChainEnd(x, int(x.size()) - 2);
    // The new subpath stops at the first vertex that is not purely specular, so a chain
    // through a mixed vertex's mirror role could not be made back (T(y -> x) = 0).
    for (int i = m + 1; m >= 0 && i < int(x.size()) - 1; ++i)
        if (x[size_t(i)].mixed) return -1;
    return m == 0 || (m > 0 && space_.connectible(x, m - 1)) ? m : -1;
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
    // The path keeps its time (the light subpath x0 .. x(m-1) stays where it was then) and
    // its wavelengths.
    const SampledWavelengths& lambda = x.back().lambda;
    Ray ray = space_.cameraRay(pFilm, Vec2(rng.uniform(), rng.uniform()), x.back().time, lambda, &camera[0]);
    ++stats.cameraPaths;
    while (true) {
        if (m + int(camera.size()) >= space_.maxVertices()) return false;
        MltVertex v;
        // A subpath that ends at the light (m = 0) may end at infinity.
        // Through media a flight may stop at a medium vertex, which ends no subpath here (the
        // proposal fails); T's cameraDensity includes the flights' densities.
        if (!space_.trace(ray, lambda, arena, stats, v, m == 0, space_.mediumFrom(camera.back(), ray.d), &rng))
            return false;
        camera.push_back(v);
        if (m == 0 ? v.light != nullptr : !v.delta) break;  // the subpath's end
        if (!v.isSpecularSurface() || !space_.scatter(camera, TransportMode::Radiance, rng, ray)) return false;
    }
    if (m > 0 && !camera.back().isNonSpecularSurface()) return false;
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
