// Veach's bidirectional mutation (thesis §11.4.2): delete a run of vertices of the path
// (its length from a distribution favouring short runs), insert a new run of a length near
// the deleted one, generated partly by a walk from the light side and partly by a walk
// from the camera side, and join the two walks with one edge.
//
// Its transition density T(x -> y) is the probability of choosing the run and the lengths,
// times the density of the inserted vertices summed over every split between the two
// walks by which they could have been generated (each split chosen with equal
// probability). Deleting the whole path regenerates it from nothing: the same sum is then
// BDPT's density with the balance heuristic over its strategies, which the bootstrap uses.
//
// With a thin lens, the split with no camera-side vertex is one of them (t = 0, thesis
// §10.2): the light walk's last ray crosses the lens, which it may when it is scattered at a
// vertex with a predecessor (paths of three vertices or more). Deleting a suffix with the
// lens may so regenerate it from the light side alone, the only way to reach L S+ E paths
// from a delta light (thesis §1.1).
//
// Which splits are possible depends only on indices (a walk cannot continue from a kept
// light vertex alone, nor from a kept thin lens) and on the camera, never on the vertices
// themselves, so the choice probabilities are the same functions of the path in both
// directions; a split whose join would end at a specular vertex has density zero.
#pragma once
#include "transport/mlt/veach/path_space.h"

namespace ps {

class BidirectionalMutation {
public:
    explicit BidirectionalMutation(const PathSpace& space) : space_(space) {}

    // Proposes y from x (y's BxDFs built in `arena`, which it resets) with T(x -> y) and
    // T(y -> x); false when the proposal fails (a ray escapes, a join is blocked): the
    // chain then stays at x.
    bool propose(const MltPath& x, Rng& rng, ScratchBuffer& arena, PathStats& stats, MltPath& y, double* Txy,
                 double* Tyx) const;
    // A whole path generated from nothing, with its density: its number of vertices
    // uniform over [2, maxVertices], then a split between the walks as above.
    bool generate(Rng& rng, ScratchBuffer& arena, PathStats& stats, MltPath& y, double* density) const;
    double generationDensity(const MltPath& y) const;

    // The parts of T, exposed for tests.
    // Probability of deleting d of a path's n vertices (then each position equally).
    static double deletionPmf(int d, int n);
    static int positions(int d, int n);
    // Probability of inserting a vertices at lo after deleting d of n (0 if impossible).
    double insertionPmf(int a, int d, int lo, int n) const;
    // T(x -> y) for y made from x by replacing x's vertices [lo, lo + d) with y's [lo, lo + a).
    double transition(const MltPath& x, const MltPath& y, int lo, int d, int a) const;
    // The density of z's vertices [lo, lo + a) summed over the possible splits, each with
    // its probability of being chosen.
    double insertedDensity(const MltPath& z, int lo, int a) const;
    // The number of splits of a vertices inserted at lo into a path of n vertices that are
    // possible (splitAllowed), each chosen with probability 1 / splits.
    int splits(int a, int lo, int n) const;
    // Whether the split that generates `c` of the a inserted vertices at lo from the light
    // side is possible in a path of n vertices.
    bool splitAllowed(int c, int a, int lo, int n) const;

    // The most vertices of a path (maxdepth 254 and below).
    static constexpr int kMaxVertices = 256;

private:
    // Every insertion's unnormalised weight after deleting d of n at lo (weights[0..
    // maxVertices - n + d]), and their sum.
    double insertionWeights(int d, int lo, int n, double* weights) const;
    // Generates vertices [lo, lo + a) of a path of n vertices between a kept prefix (lo
    // vertices) and suffix, with c of them from the light side; y receives the path.
    bool insert(const MltPath& x, int lo, int d, int a, int c, Rng& rng, ScratchBuffer& arena, PathStats& stats,
                MltPath& y) const;

    const PathSpace& space_;
};

}  // namespace ps
