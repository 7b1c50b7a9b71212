// Veach's perturbations (thesis §11.4.3): small changes that keep a path's specular
// structure, for the paths the bidirectional mutation moves poorly (a caustic seen directly,
// a light seen in a mirror, a caustic seen through glass).
//  - lens perturbation: paths ending (D|L) S* E whose D vertex connects to its predecessor.
//    The image point moves by an offset of length r in [r1, r2] with density proportional
//    to 1 / r (r1 = 0.1 pixel, r2 covering 5% of the image), in a uniform direction; the
//    new lens ray retraces the same specular bounces (reflection or transmission at each)
//    to a new D vertex, joined to the unchanged rest;
//  - multi-chain perturbation: the same where the D vertex's predecessor is specular: the
//    direction leaving each new D vertex is the old one perturbed by an angle in
//    [theta1, theta2] (density proportional to 1 / theta), through the next specular chain,
//    until a D vertex that connects (caustics seen through glass);
//  - caustic perturbation: paths ending (D|L) S+ D E: the direction leaving the (D|L)
//    vertex is perturbed likewise, the specular chain retraced to a new D vertex, which
//    connects to the lens. From a light at infinity (a direction, path_space.h) the
//    direction stays and the ray's point on the disk at infinity moves instead, by an offset
//    of length in [theta1, theta2] times the scene's radius;
// Each offset's density is symmetric (the same from y back to x), so T(y -> x) / T(x -> y)
// is the ratio of the Jacobians from the offsets to the area measure of the moved vertices:
// the retraced vertices' densities with the path's own lobes forced (their choice is not
// random here) and a unit density for the offset itself (film area or solid angle).
#pragma once
#include "transport/mlt/veach/path_space.h"

namespace ps {

struct PerturbationSizes {
    double r1 = 0.1;               // pixels
    double imageFraction = 0.05;   // r2: a disc of this fraction of the image's area
    double theta1 = 1e-4, theta2 = 0.1;  // radians (and, times the scene's radius, disk offsets)
};

class Perturbations {
public:
    Perturbations(const PathSpace& space, const PerturbationSizes& sizes = {});

    // Whether each applies to x (see above); the lens ones need a pinhole camera.
    bool lensApplies(const MltPath& x) const;
    bool multiChainApplies(const MltPath& x) const;
    bool causticApplies(const MltPath& x) const;
    // A proposal y from x (whose contribution lands at rasterX), with T(y -> x) / T(x -> y);
    // false when the retraced path fails (escapes, another specular structure, blocked).
    bool lens(const MltPath& x, Vec2 rasterX, Rng& rng, ScratchBuffer& arena, PathStats& stats, MltPath& y,
              double* ratio) const;
    bool caustic(const MltPath& x, Rng& rng, ScratchBuffer& arena, PathStats& stats, MltPath& y, double* ratio) const;

    double r2() const { return r2_; }

private:
    Vec3 perturbDirection(Vec3 w, Rng& rng) const;

    const PathSpace& space_;
    PerturbationSizes sizes_;
    double r2_;
};

}  // namespace ps
