#!/bin/sh
# The cost of the film's exact sums, end to end: renders a cheap sky scene (the film's share of
# a sample is largest there) and the shared Cornell box at equal samples with this build's
# pathspace ("now") and with the same tree whose film sums in double precision as before the
# fixed-point sums ("before": film.{h,cpp} of commit e4e9bca, with inert stand-ins for the
# exact-sum interface a one-process render never calls), alternating, and prints each one's
# best render time and the ratio.
#   bench/film_cost.sh [RUNS]     (from the repository root, after building build/pathspace)
# The before-binary is built from HEAD in build/film-before (ccache makes a rebuild quick).
set -eu
runs=${1:-3}
root=$(pwd)
dir=$root/build/film-before
now=${NOW:-$root/build/pathspace}  # NOW=binary compares another one
cornell=$root/../shared/scenes/cornell-box/scene-v4-256.pbrt

rm -rf "$dir/src" "$dir/include" "$dir/CMakeLists.txt"
mkdir -p "$dir"
git archive HEAD | tar -x -C "$dir"
git show e4e9bca:src/film/film.cpp >"$dir/src/film/film.cpp"
git show e4e9bca:src/film/film.h | sed '/^class Film {/i using Fixed = __int128;' | sed '/^class Film {/{n;a\
    struct Accumulators { std::vector<Fixed> fixed; std::vector<int64_t> counts; };\
    Accumulators accumulators() const { return {}; }\
    void setAccumulators(const Accumulators&) {}
}' >"$dir/src/film/film.h"
cmake -S "$dir" -B "$dir/build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DPATHSPACE_MPI=OFF \
    -DCMAKE_CXX_COMPILER_LAUNCHER=ccache >/dev/null
cmake --build "$dir/build" -j2 --target pathspace >/dev/null
old=$dir/build/pathspace

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# Best render time (the statistics' wall_time_s, scene loading excluded) of RUNS alternating runs.
seconds() {  # binary scene spp
    "$1" render --quiet --threads 2 --spp "$3" "$2" -o "$tmp/out.pfm" --stats "$tmp/s.json" >/dev/null
    python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['wall_time_s'])" "$tmp/s.json"
}
for case in "sky $root/bench/scenes/sky-sphere.pbrt 256" "cornell $cornell 32"; do
    set -- $case
    best_old=1e30 best_now=1e30
    for i in $(seq "$runs"); do
        t=$(seconds "$old" "$2" "$3"); best_old=$(python3 -c "print(min($best_old, $t))")
        t=$(seconds "$now" "$2" "$3"); best_now=$(python3 -c "print(min($best_now, $t))")
    done
    python3 -c "print(f'$1 ($3 spp, 2 threads, best of $runs): before {$best_old:.3f} s, now {$best_now:.3f} s, now / before {$best_now / $best_old:.3f}')"
done
