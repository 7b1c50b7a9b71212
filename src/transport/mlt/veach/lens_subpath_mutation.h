// Veach's lens subpath mutation (thesis §11.4.4): the lens subpath of a path ending
// (D|L) S* E, from the lens up to its first non-specular vertex, is replaced by a new one:
// a camera ray through a new image point, continued by sampled scattering while it meets
// specular surfaces, to the first non-specular vertex, which is joined to the unchanged rest
// (or, when the rest is empty, must be an emitter). Its T is the camera walk's density of the
// new vertices (the lens point, the film point uniform over the film, each specular lobe's
// choice); the old subpath's density is T of the way back.
//
// The film point is drawn uniformly and independently for each mutation. Veach stratified
// the points over the film across a chain's mutations; but then a chain's proposal at each
// step depends on its earlier ones (a point of a fixed sequence, not a random one), no single
// step keeps f invariant, and the image is biased: measured here, with Halton points rotated
// per chain, as blocks of the glass-caustic and mirror test scenes 6-9 sigma away from BDPT
// while the image mean agreed.
#pragma once
#include "transport/mlt/veach/path_space.h"

namespace ps {

class LensSubpathMutation {
public:
    explicit LensSubpathMutation(const PathSpace& space) : space_(space) {}
    bool applies(const MltPath& x) const;
    // y from x with a new lens subpath, and T(y -> x) / T(x -> y); false when the new
    // subpath fails (a ray escapes, the path would be too long, the join is blocked).
    bool propose(const MltPath& x, Rng& rng, ScratchBuffer& arena, PathStats& stats, MltPath& y,
                 double* ratio) const;

private:
    // The first vertex of x's lens subpath counting from the light (its non-specular end).
    int subpathStart(const MltPath& x) const;
    double subpathDensity(const MltPath& z, int start) const;

    const PathSpace& space_;
};

}  // namespace ps
