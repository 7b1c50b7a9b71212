#include "transport/mlt/veach/bidirectional_mutation.h"

#include <cmath>
#include <cstdint>
#include <cstdlib>

namespace ps {

namespace {

// 2^-m, exactly (std::ldexp's library call cost more than the rest of the weights).
double halfPower(int m) { return m < 64 ? 1.0 / double(uint64_t(1) << m) : std::ldexp(1.0, -m); }

// Unnormalised weights: deleting one vertex is most likely, then each more vertex half as
// likely (thesis §11.4.2); deleting none (a pure insertion) and deleting all (a path made
// afresh, the move that keeps the chain ergodic) get a fixed share whatever the length.
double deletionWeight(int d, int n) {
    if (d == 0 || d == n) return 0.25;
    return halfPower(d);
}

}  // namespace

double BidirectionalMutation::deletionPmf(int d, int n) {
    if (d < 0 || d > n || n < 2) return 0;
    double sum = 0;
    for (int k = 0; k <= n; ++k) sum += deletionWeight(k, n);
    return deletionWeight(d, n) / sum;
}

int BidirectionalMutation::positions(int d, int n) { return d >= 1 ? n - d + 1 : n - 1; }

bool BidirectionalMutation::splitAllowed(int c, int a, int lo, int n) const {
    const int e = a - c, suffix = n - lo - a;
    if (c < 0 || e < 0 || suffix < 0) return false;
    if (c >= 1 && !space_.canContinue(lo, TransportMode::Importance)) return false;
    if (e >= 1 && !space_.canContinue(suffix, TransportMode::Radiance)) return false;
    // No camera-side vertex: the light walk's last ray crosses a thin lens (t = 0, thesis
    // §10.2), scattered at a vertex with a predecessor (PathSpace::reachLens).
    if (suffix == 0 && e == 0) return c >= 1 && n >= 3 && space_.lensReachable();
    if (lo == 0 && a == 0) return false;
    return true;
}

int BidirectionalMutation::splits(int a, int lo, int n) const {
    int allowed = 0;
    for (int c = 0; c <= a; ++c) allowed += splitAllowed(c, a, lo, n);
    return allowed;
}

double BidirectionalMutation::insertionWeights(int d, int lo, int n, double* weights) const {
    double sum = 0;
    for (int k = 0; k <= space_.maxVertices() - n + d; ++k) {
        const int n2 = n - d + k;
        bool any = false;
        // Nothing to join, or an endpoint lost: no pure deletion there.
        if (n2 >= 2 && !(k == 0 && (d == 0 || lo == 0 || lo + d == n)))
            for (int c = 0; c <= k && !any; ++c) any = splitAllowed(c, k, lo, n2);
        weights[k] = any ? halfPower(std::abs(k - d)) : 0.0;
        sum += weights[k];
    }
    return sum;
}

double BidirectionalMutation::insertionPmf(int a, int d, int lo, int n) const {
    if (a < 0 || a > space_.maxVertices() - n + d) return 0;
    double weights[kMaxVertices + 1];
    const double sum = insertionWeights(d, lo, n, weights);
    return weights[a] > 0 ? weights[a] / sum : 0.0;
}

double BidirectionalMutation::insertedDensity(const MltPath& z, int lo, int a) const {
    const int n = int(z.size());
    // Each vertex's density from either side once; a split's density is then a product of
    // a prefix of the light side's and a suffix of the camera side's.
    double light[kMaxVertices + 1], camera[kMaxVertices + 1];
    if (a > kMaxVertices) return 0;
    camera[a] = 1;
    for (int j = a - 1; j >= 0; --j) camera[j] = camera[j + 1] * space_.cameraDensity(z, lo + j);
    light[0] = 1;
    int allowed = 0;
    double sum = 0;
    for (int c = 0; c <= a; ++c) {
        if (c > 0) light[c] = light[c - 1] * space_.lightDensity(z, lo + c - 1);
        if (!splitAllowed(c, a, lo, n)) continue;
        ++allowed;
        const int jl = lo + c - 1, jr = lo + c;
        if (jl >= 0 && jr < n && !(space_.connectible(z, jl) && space_.connectible(z, jr))) continue;
        sum += light[c] * camera[c];
    }
    return allowed > 0 ? sum / allowed : 0.0;
}

double BidirectionalMutation::transition(const MltPath& x, const MltPath& y, int lo, int d, int a) const {
    const int n = int(x.size());
    const double choose = deletionPmf(d, n) / positions(d, n) * insertionPmf(a, d, lo, n);
    return choose > 0 ? choose * insertedDensity(y, lo, a) : 0.0;
}

bool BidirectionalMutation::insert(const MltPath& x, int lo, int d, int a, int c, Rng& rng, ScratchBuffer& arena,
                                   PathStats& stats, MltPath& y) const {
    const int n = int(x.size()), n2 = n - d + a;
    arena.reset();
    std::vector<MltVertex> light(x.begin(), x.begin() + lo), camera(x.rbegin(), x.rbegin() + (n - lo - d));
    for (MltVertex& v : light) PathSpace::rebind(v, arena);
    for (MltVertex& v : camera) PathSpace::rebind(v, arena);
    // New vertices join kept ones at the path's time and wavelengths; a path made afresh
    // draws its own (each of density 1 in the state's measure: path_space.h).
    const MltVertex* kept = !light.empty() ? &light[0] : !camera.empty() ? &camera[0] : nullptr;
    const float time = kept ? kept->time : space_.drawTime(rng);
    const SampledWavelengths lambda = kept ? kept->lambda : space_.drawWavelengths(rng);
    // No camera side (t = 0): the light walk's last vertex is where its ray crosses the lens.
    const bool toLens = lo + c == n2;
    if (!space_.walk(light, toLens ? c - 1 : c, TransportMode::Importance, time, lambda, rng, arena, stats) ||
        (toLens && !space_.reachLens(light, rng, arena, stats)) ||
        !space_.walk(camera, a - c, TransportMode::Radiance, time, lambda, rng, arena, stats))
        return false;
    if (int(light.size()) != lo + c || int(camera.size()) != n2 - lo - c) return false;
    y.assign(light.begin(), light.end());
    y.insert(y.end(), camera.rbegin(), camera.rend());
    if (light.empty()) return y[0].light != nullptr;  // the camera walk ended on an emitter
    if (camera.empty()) return true;                  // the light walk crossed the lens
    const int jl = lo + c - 1, jr = lo + c;
    y[size_t(jl)].takeJoinRole();
    y[size_t(jr)].takeJoinRole();
    return space_.connectible(y, jl) && space_.connectible(y, jr) && space_.visible(y[size_t(jl)], y[size_t(jr)], stats);
}

bool BidirectionalMutation::propose(const MltPath& x, Rng& rng, ScratchBuffer& arena, PathStats& stats, MltPath& y,
                                    double* Txy, double* Tyx) const {
    const int n = int(x.size());
    int d = 0;
    for (double u = rng.uniformDouble(); d < n; ++d) {
        u -= deletionPmf(d, n);
        if (u < 0) break;
    }
    const int lo = d >= 1 ? int(rng.uniformInt(uint32_t(n - d + 1))) : 1 + int(rng.uniformInt(uint32_t(n - 1)));
    const int aMax = space_.maxVertices() - n + d;
    double weights[kMaxVertices + 1];
    const double sum = insertionWeights(d, lo, n, weights);
    int a = -1;
    double u = rng.uniformDouble();
    for (int k = 0; k <= aMax; ++k) {
        const double p = weights[k] > 0 ? weights[k] / sum : 0.0;
        if (p > 0) {
            a = k;
            if ((u -= p) < 0) break;
        }
    }
    if (a < 0) return false;
    const int n2 = n - d + a;
    int pick = int(rng.uniformInt(uint32_t(splits(a, lo, n2)))), c = 0;
    for (;; ++c)
        if (splitAllowed(c, a, lo, n2) && pick-- == 0) break;
    if (!insert(x, lo, d, a, c, rng, arena, stats, y)) return false;
    *Txy = transition(x, y, lo, d, a);
    *Tyx = transition(y, x, lo, a, d);
    return true;
}

bool BidirectionalMutation::generate(Rng& rng, ScratchBuffer& arena, PathStats& stats, MltPath& y,
                                     double* density) const {
    const int n = 2 + int(rng.uniformInt(uint32_t(space_.maxVertices() - 1)));
    int pick = int(rng.uniformInt(uint32_t(splits(n, 0, n)))), c = 0;
    for (;; ++c)
        if (splitAllowed(c, n, 0, n) && pick-- == 0) break;
    if (!insert(MltPath(), 0, 0, n, c, rng, arena, stats, y)) return false;
    *density = generationDensity(y);
    return *density > 0;
}

double BidirectionalMutation::generationDensity(const MltPath& y) const {
    return insertedDensity(y, 0, int(y.size())) / double(space_.maxVertices() - 1);
}

}  // namespace ps
