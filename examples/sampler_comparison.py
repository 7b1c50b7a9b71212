"""The toolbox's point sets on a smooth 2D integrand: error against the number of points.

    PYTHONPATH=build/python /usr/bin/python3 examples/sampler_comparison.py

Independent points converge as n^-1/2 in RMS error; stratified ones as n^-1 on a smooth 2D
integrand; Latin hypercube helps only with the additive part of f (none here: it stays near
n^-1/2); scrambled Sobol converges faster still. Prints each point set's fitted slope and
writes sampler_comparison.png.
"""
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import pathspace


def f(x):  # integral over [0,1)^2: (1 - cos 1) * sin 1
    return np.sin(x[:, 0]) * np.cos(x[:, 1])


exact = (1 - np.cos(1.0)) * np.sin(1.0)
counts = [2 ** k for k in range(4, 15, 2)]
for name in ["independent", "stratified", "lhs", "sobol"]:
    rms = []
    for n in counts:
        errors = [f(pathspace.mc.points(name, n, 2, seed)).mean() - exact for seed in range(32)]
        rms.append(float(np.sqrt(np.mean(np.square(errors)))))
    slope = np.polyfit(np.log(counts), np.log(rms), 1)[0]
    print(f"{name:12s} RMS error ~ n^{slope:.2f}")
    plt.loglog(counts, rms, "o-", label=f"{name} (slope {slope:.2f})")
plt.xlabel("points")
plt.ylabel("RMS error")
plt.legend()
plt.savefig("sampler_comparison.png", dpi=120)
print("wrote sampler_comparison.png")
