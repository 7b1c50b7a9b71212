// Paths as points of path space (thesis ch. 8), the state of Veach's Metropolis light
// transport (thesis ch. 11): the vertices x0 (on a light) ... xk (on the lens) themselves,
// not the random numbers that made them. A mutation keeps some vertices and generates
// others by the same local sampling BDPT uses, and its acceptance needs, for any path, the
// measurement contribution f(x) and the area density with which each vertex could have
// been generated from either side; this class gives them.
//
// Conventions, shared by f and the densities so that every delta cancels:
//  - f uses the BSDFs for light flowing from x0 to xk (radiance transport) with the
//    shading-normal correction of the path tracer (thesis §5.3), so its f / p equals the
//    path tracer's, BDPT's and light tracing's estimates;
//  - a specular vertex stands for its lobe's weight per unit solid angle, and its
//    "density" for the discrete probability of choosing that lobe (both times one delta, in
//    the light-side direction: a density from the light side, whose delta is in the
//    camera-side direction, carries the refraction's Jacobian, lightDensity);
//  - the pinhole's position and a point light's are deltas of unit weight;
//  - the lens has the viewing direction as its normal, so the geometry term of the last
//    edge carries the lens cosine that the importance We expects;
//  - a thin lens is a disk of the scene that a light walk's ray may cross (Veach's t = 0
//    paths, thesis §10.2): the lens vertex's density from the light side is then the
//    scattering's direction density at x_{k-1} times |cos at the lens| / d^2, as for any
//    surface; a pinhole is a delta no ray hits (density 0 from the light side);
//  - a light vertex at infinity (an infinite or a distant light: atInfinity) is a direction,
//    not a point. The thesis' path space (ch. 8) takes each vertex in the area measure of
//    the scene's surfaces; a vertex at infinity takes the solid-angle measure of the sphere
//    of directions instead (as BDPT's vertices do, README "Metropolis"), so that:
//      the geometry term of its edge is |cos| at the other vertex alone (no distance);
//      its density from the light side is the lights' direction density (summed over the
//      infinite lights: the vertex stands for all of them, whose radiance f sums, as an
//      escaped camera ray of BDPT does), or for a distant light a delta of unit weight;
//      the next vertex's density from the light side is the area density of the disk at
//      infinity that the emitted rays start from, times |cos| there (the disk faces the
//      direction);
//      its density from the camera side is the solid-angle density of the direction
//      scattered at its neighbour, met by a ray that escapes the scene (zero for a distant
//      light's delta direction);
//    and a join to it is a shadow ray along its direction. Its `ng` holds the direction
//    the light travels (into the scene), so cosAt(x0, edge) is 1.
#pragma once
#include <atomic>
#include <optional>
#include <vector>
#include "geometry/interaction.h"
#include "lights/light.h"
#include "materials/bxdf.h"
#include "math/frame.h"
#include "mc/rng.h"
#include "render/scene.h"
#include "spectral/wavelengths.h"
#include "transport/integrator.h"
#include "transport/spectral_film.h"
#include "util/scratch.h"

namespace ps {

struct MltVertex {
    // Medium: a scattering point in a participating medium (path_space_media.cpp), whose
    // "BSDF" is the phase function times sigma_s, and whose measure is volume (no cosine).
    enum class Kind : uint8_t { Light, Surface, Lens, Medium };
    Kind kind = Kind::Surface;
    // Surfaces: no diffuse or glossy lobe (specular ones only, or none: black), or a mixed
    // surface's mirror role; lights: a delta position or direction (isDeltaLight).
    bool delta = false;
    // A layered surface (BxDF::stochastic): sampled by PathSpace's own mixture of known
    // density, its coating's mirror reflection (probability R(wo), the Fresnel reflectance)
    // or a cosine lobe on wo's side. `delta` is then this path's choice at the vertex: the
    // mirror role (S) when the path reflects in the coating, else the rest of the BxDF (D),
    // whose f is the layered estimate (deterministic in the directions). A vertex where the
    // path is joined is always D.
    bool mixed = false;
    Vec3 p;
    Vec3 ng;             // geometric normal; zero for a point (point light, pinhole); lens: the view axis
    Vec3 ns;             // shading normal (surfaces)
    Vec2 uv;
    // The path's scene time (motion blur): every vertex of a path has it, and every ray
    // leaving one travels at it.
    float time = 0;
    // Spectral mode: the path's wavelengths, which every vertex of a path has, as its time:
    // its BxDFs are built, its emission and its contribution evaluated at them (all zero in
    // RGB mode). A path's wavelengths are part of the chain's state, drawn from the
    // sensor's wavelength density, whose measure the state space takes for them, so that a
    // fresh draw has density 1 and a kept one cancels in T (README "Metropolis").
    SampledWavelengths lambda;
    // A surface whose BxDF follows lambda[0] alone (dispersion): the path's contribution
    // then keeps only that wavelength (SampledWavelengths::terminateSecondary).
    bool dispersive = false;
    Frame frame;         // shading frame (surfaces)
    const Light* light = nullptr;  // the emitter at x0 (a light vertex or an emitting surface)
    const BxDF* bxdf = nullptr;    // surfaces, built in the owning path's arena
    SurfaceInteraction si;         // surfaces: the hit as traced, to rebuild bxdf in another arena
    // Scenes with media: the medium on each side of the vertex (above: where ng points), that
    // a ray leaving it enters; both the same off medium boundaries, and for a medium vertex.
    const Medium* mediumAbove = nullptr;
    const Medium* mediumBelow = nullptr;
    const Medium* mediumToward(Vec3 w) const { return dot(w, ng) > 0 ? mediumAbove : mediumBelow; }
    bool isMedium() const { return kind == Kind::Medium; }

    // A light vertex at a delta position or direction (a point, spot or distant light). Only a
    // light vertex's `delta` says so: an emitter that a camera walk hits is a surface vertex,
    // which is S wherever its BSDF has no diffuse or glossy lobe (a black one has none), but
    // as x0 it is an area light like any other, whichever walk made it.
    bool isDeltaLight() const { return kind == Kind::Light && delta; }
    // A scattering vertex with a diffuse or glossy lobe (D), or with specular lobes only (S).
    bool isNonSpecularSurface() const { return kind == Kind::Surface && bxdf && !delta; }
    bool isSpecularSurface() const { return kind == Kind::Surface && bxdf && delta; }
    // Takes the specular role if the surface has one (a retraced chain keeps a path's roles).
    bool takeSpecularRole() {
        if (mixed) delta = true;
        return isSpecularSurface();
    }
    // A mixed vertex where a path is joined takes the D role.
    void takeJoinRole() {
        if (mixed) delta = false;
    }
};

using MltPath = std::vector<MltVertex>;

// A light walk's ray that crossed a thin lens: the lens vertex that ends the t = 0 path of the
// walk's first `index` vertices (thesis §10.2).
struct MltLensHit {
    int index = 0;
    MltVertex lens;
};

// The numbers that start a new walk, given in place of its stream's: a stratified bootstrap
// sample (veach_mlt.cpp). For a light walk the light's choice, its point's and its direction's;
// for a camera walk the film's and the lens's (choice unused); then the first scattering's
// lobe and direction, at a surface (a medium's scattering takes the stream's).
struct WalkStart {
    float choice = 0;
    Vec2 point, direction;
    float lobe = 0;
    Vec2 scatter;
};

class PathSpace {
public:
    PathSpace(const Scene& scene, int maxDepth);
    const Scene& scene() const { return scene_; }
    int maxDepth() const { return maxDepth_; }
    // Vertices of the longest path: a light, maxDepth scattering vertices, the lens.
    int maxVertices() const { return maxDepth_ + 2; }
    bool pinhole() const { return pinhole_; }

    // f(x), the measurement contribution of the whole path (visibility of its edges is
    // established when they are made), with the film position it lands at; zero where any
    // factor is. In spectral mode, the sensor's RGB of its values at the path's wavelengths
    // (divided by their density: the state's measure, path_space.h MltVertex::lambda).
    // In a scene with media, the transmittance of every edge enters f; where a medium is not
    // homogeneous it is a ratio-tracking estimate drawn from *rng (unbiased and non-negative:
    // the pseudo-marginal chain, path_space_media.cpp), so f is then random and callers keep
    // the value they got with the state.
    Spectrum contribution(const MltPath& x, Vec2* pRaster, Rng* rng = nullptr) const;
    bool spectral() const { return sensor_.has_value(); }
    // Area density (solid angle for a light vertex at infinity) of vertex i when
    // generated from the light side, given vertices i - 1 and i - 2, and from the camera side,
    // given i + 1 and i + 2. Vertex 0 from the light side: the light's choice and position;
    // the last from the camera side: the lens position; the last from the light side: a ray
    // from x_{k-1} crossing a thin lens (reachLens; zero for a pinhole, and for k < 2: a
    // light seen directly is the camera side's, as in BDPT, transport/lens_hits.h).
    // `Density` says what a specular vertex's lobe counts for: its probability of being
    // chosen (Sampled: a walk chose it), or 1 (Forced: a perturbation keeps the path's own
    // lobes, and only the geometry of the retraced chain changes the density).
    // With media, Sampled includes the free flight that reached vertex i (flightDensity); a
    // Forced retrace passes through media without sampling them, so it has none.
    enum class Lobes { Sampled, Forced };
    double lightDensity(const MltPath& x, int i, Lobes lobes = Lobes::Sampled) const;
    double cameraDensity(const MltPath& x, int i, Lobes lobes = Lobes::Sampled) const;
    // The factor |cos at x[to]| / d^2 that turns a unit direction density at x[from] into an
    // area density at x[to]; 1 for x[to] at infinity (its measure is solid angle); for x[from]
    // at infinity, |cos at x[to]|, turning a unit area density on the disk at infinity that
    // faces the direction into an area density at x[to].
    static double areaFactor(const MltPath& x, int from, int to);
    // Whether a connection (a deterministic edge) can end at vertex i of x: the light
    // endpoint, the lens, or a surface with a non-specular lobe.
    bool connectible(const MltPath& x, int i) const;
    // Counting down from vertex `from` over specular surfaces, the first vertex that is not
    // one: its index m, or -1 if it is neither a non-specular surface nor (m = 0) a light
    // that a ray can hit (the end of a specular chain that a retraced or new chain of
    // camera rays must reach).
    int specularChainEnd(const MltPath& x, int from) const;

    // A new path's scene time: uniform over the shutter when the scene moves (in the
    // shutter's measure normalised to 1, so that no density changes), else the shutter's
    // opening without drawing a number (static scenes keep their random streams).
    float drawTime(Rng& rng, const float* given = nullptr) const;
    // A new path's wavelengths in spectral mode (the sensor's density); in RGB mode none, and
    // no number drawn. With `given`, that number in place of the stream's (as WalkStart).
    SampledWavelengths drawWavelengths(Rng& rng, const float* given = nullptr) const;
    // Wavelengths near `lambda` (spectral mode; in RGB mode `lambda` itself, no number
    // drawn): sampleVisible's number moved by an offset of random sign and of length with
    // density proportional to 1 / length in [1e-3, 1/4] (one stratum of the four), wrapping
    // around [0, 1). Symmetric in that number, whose uniform measure is the state's for the
    // wavelengths: T(y -> x) / T(x -> y) = 1. The perturbations use it, so that a path
    // through a dispersive vertex, which only lambda[0] follows, changes colour as it moves.
    SampledWavelengths perturbWavelengths(const SampledWavelengths& lambda, Rng& rng) const;
    // Walks that append `count` vertices to `side`, a subpath in walk order: from the light
    // (Importance: side[0] is x0) or from the lens (Radiance: side[0] is xk), at scene time
    // `time` (a non-empty side's own). An empty side
    // starts on a light chosen by power or at a new film point; a light side cannot continue
    // from its light vertex alone, nor a camera side from a thin lens alone (no density
    // of a direction given a fixed point there); a pinhole's is regenerated. False when a
    // ray escapes or a sample fails.
    // With `start` (an empty side), the walk's first numbers are its values (the stream still
    // draws its own, so that the rest of the stream is the same).
    // With `lensHits` (a light walk through a thin lens), every lens crossing of a ray
    // scattered at a vertex with a predecessor is recorded as the lens vertex that the t = 0
    // path of the vertices before it would end with (the walk goes on: the lens is no
    // obstacle), as BDPT's light subpaths record theirs.
    bool walk(std::vector<MltVertex>& side, int count, TransportMode mode, float time, const SampledWavelengths& lambda,
              Rng& rng, ScratchBuffer& arena, PathStats& stats, const WalkStart* start = nullptr,
              std::vector<MltLensHit>* lensHits = nullptr) const;
    // Whether walk can extend a side (light or camera, by `mode`) that holds `size` vertices.
    bool canContinue(int size, TransportMode mode) const;
    // Whether light walks can reach the lens: a thin lens (Camera::hasLensDisk).
    bool lensReachable() const { return lensReachable_; }
    // The t = 0 step (thesis §10.2): appends to a light side of at least two vertices the lens
    // vertex where the ray scattered at its last vertex crosses the lens disk, if nothing
    // stops the ray before (a surface, a free flight's collision). False otherwise.
    bool reachLens(std::vector<MltVertex>& side, Rng& rng, ScratchBuffer& arena, PathStats& stats) const;
    // Mutual visibility of vertices a and b.
    bool visible(const MltVertex& a, const MltVertex& b, PathStats& stats) const;
    // The next ray of a walk: a direction sampled by the BSDF at side's last vertex (which
    // must have a predecessor in side).
    // A mixed vertex's role is chosen here.
    // With `start`, its lobe and direction numbers in place of the stream's (at a surface).
    bool scatter(std::vector<MltVertex>& side, TransportMode mode, Rng& rng, Ray& ray,
                 const WalkStart* start = nullptr) const;
    // A camera ray through film point pFilm (a pinhole's lens point is fixed; a thin lens
    // takes its point from uLens) at scene time `time`, and the lens vertex it leaves, which
    // carries `lambda`.
    Ray cameraRay(Vec2 pFilm, Vec2 uLens, float time, const SampledWavelengths& lambda, MltVertex* lens) const;
    // The film, widened by the filter radius: where camera rays may pass.
    Vec2 filmMargin() const { return margin_; }
    Vec2 filmSize() const { return filmSize_; }
    bool sawUnsupportedSurface() const { return unsupportedSurface_.load(std::memory_order_relaxed); }
    // Rebuilds a surface vertex's BxDF in `arena` (a path's vertices must all live in its own),
    // at its wavelengths.
    static void rebind(MltVertex& v, ScratchBuffer& arena);
    // y = x at wavelengths `lambda`, its BxDFs rebuilt in `arena` (which is reset first).
    static void copyAt(const MltPath& x, const SampledWavelengths& lambda, ScratchBuffer& arena, MltPath& y);
    // Whether the light at specular vertex i of x is reflected (else transmitted).
    static bool reflects(const MltPath& x, int i);
    // Traces the ray to the next vertex (passing through interfaces), whose BxDF is built at
    // `lambda` (the path's; the vertex keeps them): false if it escapes, or
    // if it meets a layered surface whose mirror part lies under a smooth coating (then
    // sawUnsupportedSurface() turns true: the renderer refuses the scene).
    // With `escape`, a ray that leaves the scene ends on the infinite lights, if the scene
    // has any: `out` is then a light vertex at infinity (a camera-side walk's end).
    // In a scene with media, `medium` is the ray's (updated at each boundary it crosses) and,
    // given `flights`, the ray may stop at a medium vertex, drawn from the majorants' Poisson
    // process (flightDensity); without, it passes through the media (a perturbation's retrace).
    // With `lens` (a thin lens), a crossing of the lens disk before the ray stops (or escapes)
    // is written there as a lens vertex (kind Lens; left alone otherwise), whatever the return.
    bool trace(Ray ray, const SampledWavelengths& lambda, ScratchBuffer& arena, PathStats& stats, MltVertex& out,
               bool escape = false, const Medium* medium = nullptr, Rng* flights = nullptr,
               MltVertex* lens = nullptr) const;
    // The medium a ray leaving v along w starts in (the camera's at the lens, a light's side).
    const Medium* mediumFrom(const MltVertex& v, Vec3 w) const;

    // Scenes with media (path_space_media.cpp). The density with which a free flight from a
    // towards b ends at b: exp(-integral of the majorant) over the edge, times the majorant at
    // b if b is a medium vertex (per unit length, which the volume measure's 1 / d^2 makes
    // per unit volume). The majorant is the largest channel's of each medium's majorant
    // segments: a deterministic function of the path (at its wavelengths), so that T is.
    double flightDensity(const MltVertex& a, const MltVertex& b) const;
    // The transmittance of the edge a-b through the media and `interface` shapes on it
    // (zero if another surface blocks it): exact in homogeneous media, else ratio tracking
    // against the same majorant (each factor 1 - sigma_t / majorant >= 0), drawn from rng.
    Spectrum edgeTransmittance(const MltVertex& a, const MltVertex& b, Rng* rng, PathStats* stats = nullptr) const;
    // Continues a retraced specular chain at specular vertex v, reached along `ray`, by the
    // lobe that reflects or transmits as asked: the next ray, or false if v has no such lobe.
    bool followSpecular(const MltVertex& v, const Ray& ray, bool reflect, TransportMode mode, Ray& next) const;

    // The direction density, per solid angle, with which a light walk starts at infinity
    // vertex v: the infinite lights' own summed (each chosen with its probability), or a
    // distant light's choice (its direction a delta of unit weight).
    double infinityDensity(const MltVertex& v) const;
    // The radiance x0 sends towards x1 (an area light's, a point light's intensity, the sum
    // of the infinite lights' along the direction, a distant light's).
    Spectrum emitted(const MltVertex& x0, const MltVertex& x1) const;

private:
    // The BSDF at surface vertex v for light arriving from direction wi and leaving along wo
    // (unit, world), in `mode`, with the density of sampling wi from wo; specular lobes
    // matched to the direction pair. At a specular vertex, `jacobian` receives
    // d(omega_wo) / d(omega_wi) along its lobe's map from wo to wi (1 for a reflection; for a
    // refraction eta'^2 |cos wi| / |cos wo|, eta' the ratio of wi's index to wo's), else 1.
    void bsdf(const MltVertex& v, Vec3 wo, Vec3 wi, TransportMode mode, Spectrum* f, float* pdf,
              float* jacobian = nullptr) const;
    // A free flight along ray (in `medium`, up to tEnd) by the majorant's Poisson process:
    // the first tentative collision, if before tEnd (path_space_media.cpp).
    static bool sampleFlight(const Medium& medium, const Ray& ray, float tEnd, const SampledWavelengths& lambda,
                             Rng& rng, Vec3* p);
    // The free flight of trace: a medium vertex in `out` if it stops before tEnd.
    bool traceInMedium(const Ray& ray, float tEnd, const Medium& medium, const SampledWavelengths& lambda, Rng& rng,
                       MltVertex& out) const;
    // scatter at a medium vertex: the phase function's direction.
    bool scatterInMedium(std::vector<MltVertex>& side, Rng& rng, Ray& ray) const;
    bool visibleThroughMedia(const MltVertex& a, const MltVertex& b, PathStats& stats) const;
    // A shadow ray from `from` (offset off its surface along fromNg, if not zero) to vertex
    // `to`, stopped short of `to` by the offset a ray leaving `to` would get (tMax <= 0: too
    // short for anything to block). spawnRayTo's relative margin alone is below the
    // intersection's rounding on edges shorter than about 1e-3, which media make common (a
    // free flight stops anywhere): a ray from a medium vertex, which has no offset, then hit
    // the surface of the vertex it went to, and the edge counted as blocked from that end
    // alone (a zero density from one side, a path weight of 1e10 in the bootstrap).
    static Ray shadowRay(Vec3 from, Vec3 fromNg, const MltVertex& to, float time);
    // Walks the edge a-b (from its finite end, the optical depth being the same either way)
    // through `interface` shapes: calls part(medium, origin, unit direction, length) for each
    // piece in a medium, which may end the walk (false); false if a surface that is not an
    // interface blocks the edge.
    template <typename Part>
    bool alongEdge(const MltVertex& a, const MltVertex& b, PathStats* stats, Part&& part) const;

    // The lens vertex at world point p (on the lens) at scene time `time`.
    MltVertex lensVertex(Vec3 p, float time, const SampledWavelengths& lambda) const;

    const Scene& scene_;
    int maxDepth_;
    bool pinhole_, lensReachable_;
    Vec2 margin_, filmSize_;
    mutable std::atomic<bool> unsupportedSurface_{false};
    std::optional<SpectralFilm> sensor_;  // spectral mode's sensor (empty in RGB mode)
};

// Whether v is a light vertex at infinity (an infinite or a distant light; see the top).
inline bool atInfinity(const MltVertex& v) {
    return v.kind == MltVertex::Kind::Light && v.light && v.light->atInfinity();
}

// The unit direction from vertex `from` towards vertex `to`, either of which may lie at
// infinity (its `ng` is the direction its light travels).
inline Vec3 directionTo(const MltVertex& from, const MltVertex& to) {
    if (atInfinity(to)) return -to.ng;
    if (atInfinity(from)) return from.ng;
    return normalize(to.p - from.p);
}

// |cos| at v of the direction w (1 for a point without a normal). On a flat curve, which
// faces each ray, the fibre's projected width sqrt(1 - (w . axis)^2) instead: the path's
// measure there is the fibre's area, whichever ray found the point (as densityCos in
// transport/path_vertex.h).
inline float cosAt(const MltVertex& v, Vec3 w) {
    if (v.kind == MltVertex::Kind::Surface && v.si.fibre == FibreKind::FacingRay) {
        const float a = dot(v.frame.s, w);
        return std::sqrt(std::max(0.0f, 1 - a * a));
    }
    return (v.ng.x != 0 || v.ng.y != 0 || v.ng.z != 0) ? std::fabs(dot(v.ng, w)) : 1.0f;
}

}  // namespace ps
