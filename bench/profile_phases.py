#!/usr/bin/env python3
"""Where a render's time goes, by phase, from a `perf record` profile (bench/README.md,
"Where the time goes"). Usage:

  perf record -e cpu-clock -o perf.data ./build/pathspace render SCENE --threads 1 --quiet -o /tmp/x.pfm
  python3 bench/profile_phases.py perf.data

Each sampled symbol goes to the first phase whose pattern it matches; the rest is "other".
"""
import re
import subprocess
import sys

PHASES = [
    ("intersection (Embree)", r"libembree|Scene::intersect|Scene::occluded|TriangleMesh::interaction|"
                              r"Quadric::interaction|Curve.*interaction|rtc"),
    ("light sampling", r"LightSampler|sampleToward|sampleLi|sampleDirect|sampleLight|lightPmf|pdfLi|"
                       r"LightImportance|AliasTable|joinLight|lightChoiceRatio"),
    ("BSDF construction and evaluation", r"Material::bxdf|BxDF|bxdf|Fresnel|Microfacet|Trowbridge"),
    ("spectra", r"Spectrum|Wavelength|toRendering|Spectral|Sigmoid|blackbody"),
    ("sampler", r"Sampler::|Sobol|Halton|Rng|sampleDimension|get1D|get2D"),
    ("film and filter", r"Film::|Filter::|addSample|addSplat|splat"),
    ("camera", r"Camera::"),
    ("integrator (walk, MIS, connections)", r"PathTracer|BDPT|Subpaths|randomWalk|misWeight|misPrefixes|"
                                            r"connect|estimate|produce|join"),
    ("scheduling and threads", r"SamplePasses|tbb|libtbb|std::function"),
    ("kernel", r"\[kernel|kallsyms|pvm_"),
]


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    out = subprocess.run(["perf", "report", "-i", sys.argv[1], "--no-children", "--sort", "dso,symbol",
                          "--stdio"], capture_output=True, text=True, check=True).stdout
    totals = {name: 0.0 for name, _ in PHASES}
    totals["other"] = 0.0
    for line in out.splitlines():
        m = re.match(r"\s+([0-9.]+)%\s+(.*)$", line)
        if not m:
            continue
        share, rest = float(m.group(1)), m.group(2)
        # A function's own name decides, not its template arguments (estimate<PaddedSobolSampler>).
        while re.search(r"<[^<>]*>", rest):
            rest = re.sub(r"<[^<>]*>", "", rest)
        for name, pattern in PHASES:
            if re.search(pattern, rest):
                totals[name] += share
                break
        else:
            totals["other"] += share
    for name, share in sorted(totals.items(), key=lambda kv: -kv[1]):
        print(f"{share:6.1f}%  {name}")


if __name__ == "__main__":
    main()
