"""pathspace.mc.estimate and .convergence: the toolbox's techniques on a vectorised integrand.

f(x) = prod_i e^{x_i} over [0,1)^3 has the integral (e - 1)^3; it is monotone in every
coordinate (antithetic and the control sum(x_i) help) and separable (its partial integral and
an importance density proportional to it are known in closed form).
"""
import math

import numpy as np
import pytest

DIMS = 3
EXACT = (math.e - 1) ** DIMS


def f(x):
    return np.exp(x.sum(axis=1))


def partial(x):  # f integrated over the last coordinate: a function of the first DIMS-1
    return np.exp(x.sum(axis=1)) * (math.e - 1)


def sample(u):  # inversion of the density prod e^{x_i}/(e-1), proportional to f
    return np.log1p(u * (math.e - 1))


def pdf(x):
    return np.exp(x.sum(axis=1)) / (math.e - 1) ** DIMS


EXTRAS = {"expected": {"partial": partial}, "importance": {"importance": (sample, pdf)}}


def estimate(pathspace, technique, n=4096, seed=1, g=f):
    return pathspace.mc.estimate(g, DIMS, n, technique=technique, seed=seed, **EXTRAS.get(technique, {}))


def test_every_technique_estimates_a_known_integral(pathspace):
    names = [name for name, _ in pathspace.mc.techniques()]
    assert names[:4] == ["independent", "stratified", "lhs", "sobol"] and "two-stage" in names
    for name in names:
        e = estimate(pathspace, name)
        assert abs(e.value - EXACT) < 5 * e.standard_error + 1e-9, (name, e)
        assert 1000 <= e.evaluations <= 4096, (name, e.evaluations)  # roulette about n/2, the grid 16^3
        assert e.seconds > 0 and e.variance == pytest.approx(e.standard_error ** 2)
        if e.variance > 0:
            assert e.efficiency == pytest.approx(1 / (e.variance * e.seconds))


def test_independent_is_the_mean_over_the_toolbox_points_in_one_call(pathspace):
    calls = []

    def g(x):
        calls.append(np.array(x))
        return f(x)

    e = estimate(pathspace, "independent", n=1000, seed=7, g=g)
    points = pathspace.mc.points("independent", 1000, DIMS, 7)
    assert len(calls) == 1 and np.array_equal(calls[0], points)
    assert e.value == pytest.approx(f(points).mean(), rel=1e-12)
    assert e.evaluations == 1000


def test_variance_reduction_against_independent_points(pathspace):
    plain = estimate(pathspace, "independent").variance
    assert estimate(pathspace, "antithetic").variance < plain / 5      # f monotone: pairs anti-correlated
    assert estimate(pathspace, "control").variance < plain / 5         # sum(x_i) follows f's trend
    assert estimate(pathspace, "regression").variance < plain / 5
    assert estimate(pathspace, "expected").variance < plain            # one coordinate integrated exactly
    assert estimate(pathspace, "roulette").variance > plain            # cheaper, noisier
    e = estimate(pathspace, "importance")                              # pdf proportional to f: no variance
    assert e.value == pytest.approx(EXACT, rel=1e-12) and e.standard_error < 1e-9


def test_importance_density_and_f_see_only_sampled_points(pathspace):
    seen = {"sample": [], "pdf": [], "f": []}

    def spy(name, fn):
        def wrapped(x):
            seen[name].append(np.array(x))
            return fn(x)
        return wrapped

    pathspace.mc.estimate(spy("f", f), DIMS, 256, technique="importance", seed=3,
                          importance=(spy("sample", sample), spy("pdf", pdf)))
    assert [len(seen[k]) for k in ("sample", "pdf", "f")] == [1, 1, 1]
    sampled = sample(seen["sample"][0])
    assert np.array_equal(seen["pdf"][0], sampled) and np.array_equal(seen["f"][0], sampled)


def test_two_stage_converges_to_the_integral_of_a_peak(pathspace):
    # A narrow peak: the second stage's allocation depends on the pilots' values, so the
    # estimator is run again from their values before the rest of the points are asked for.
    def peak(x):
        return np.exp(-200 * ((x - 0.3) ** 2).sum(axis=1))

    exact = (math.sqrt(math.pi / 200) / 2 * (math.erf(0.7 * math.sqrt(200)) + math.erf(0.3 * math.sqrt(200)))) ** 2
    study = pathspace.mc.convergence(peak, 2, exact, [1024], technique="two-stage", runs=24, seed=5)
    p = study["points"][0]
    assert abs(p["mean"] - exact) < 4 * p["standard_error"] / math.sqrt(24)
    plain = pathspace.mc.convergence(peak, 2, exact, [1024], runs=24, seed=5)["points"][0]
    assert p["rmse"] < plain["rmse"] / 2


def test_convergence_slopes(pathspace):
    ns = [64, 256, 1024, 4096]
    slope = {t: pathspace.mc.convergence(f, 2, (math.e - 1) ** 2, ns, technique=t, runs=32, seed=2)["slope"]
             for t in ["independent", "stratified", "sobol"]}
    assert -0.65 < slope["independent"] < -0.35
    assert slope["stratified"] < -0.85 and slope["sobol"] < -0.85
    study = pathspace.mc.convergence(f, 2, (math.e - 1) ** 2, [256], runs=4)
    assert set(study["points"][0]) == {"n", "evaluations", "mean", "standard_error", "reported_error", "rmse",
                                       "seconds", "efficiency"}


def test_bad_calls(pathspace):
    mc = pathspace.mc
    with pytest.raises(ValueError, match='unknown technique "halton"'):
        mc.estimate(f, 2, 64, technique="halton")
    with pytest.raises(ValueError, match="needs partial="):
        mc.estimate(f, 2, 64, technique="expected")
    with pytest.raises(ValueError, match=r"needs importance=\(sample, pdf\)"):
        mc.estimate(f, 2, 64, technique="importance")
    with pytest.raises(ValueError, match="up to 10 dimensions"):
        mc.estimate(f, 11, 64, technique="sobol")
    with pytest.raises(ValueError, match=r"f returned an array of shape \(64, 2\) for 64 points; expected \(64,\)"):
        mc.estimate(lambda x: x, 2, 64)
    with pytest.raises(ValueError, match="at least 1"):
        mc.estimate(f, 2, 0)
    with pytest.raises(ValueError, match="runs must be at least 2"):
        mc.convergence(f, 2, 1.0, [64], runs=1)
    with pytest.raises(ZeroDivisionError):
        mc.estimate(lambda x: 1 / 0, 2, 64)
