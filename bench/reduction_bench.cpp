// The film reduction alone: what a render over K processes adds at its end (and at every
// checkpoint), each process's film sums (Film::accumulators: 128-bit fixed-point sums and
// 64-bit counts) added into rank 0's with MPI_Reduce, per image size, without rendering.
//   mpirun --oversubscribe --allow-run-as-root --bind-to core -n 2 build/bench/reduction_bench --sizes 256 1024 4096
// Prints one JSON line per size (rank 0): the bytes each process sends; the seconds of the
// reduction alone (first, best, median) and with a copy of the whole film out of it and back
// (median); and of the renderer's chunked reduction straight from the film (best, median).
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <vector>

#include "film/film.h"
#include "render/distributed.h"

using namespace ps;

namespace {

double now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
    distributed::start(argc, argv);
    CLI::App app{"Times the film reduction of a render over several processes (run it under mpirun)"};
    std::vector<int> sizes{256, 1024, 4096};
    int runs = 5;
    app.add_option("--sizes", sizes, "Square image sizes (pixels per side)");
    app.add_option("--runs", runs, "Timed reductions per size")->check(CLI::PositiveNumber);
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return distributed::finish(app.exit(e) == 0 ? 0 : 2);
    }
    for (int n : sizes) {
        Film film(n, n, PixelBounds{0, n, 0, n});
        for (int y = 0; y < n; y += 7)  // some non-zero sums (the reduction's cost does not depend on them)
            for (int x = 0; x < n; x += 5) film.addSample(x, y, Spectrum(0.25f * float(distributed::rank() + 1)), 1.0f);
        std::vector<double> reduce, whole, chunked;
        double bytes = 0;
        for (int r = 0; r < runs; ++r) {
            // A copy of the whole film's sums (Film::accumulators), summed on rank 0 (timed
            // alone, between barriers, as the statistics' film reduction) and copied back.
            distributed::barrier();
            const double t0 = now();
            Film::Accumulators sums = film.accumulators();
            const double copied = now() - t0;
            distributed::barrier();
            const double t1 = now();
            distributed::sumToRoot(sums.fixed);
            distributed::sumToRoot(sums.counts);
            const double t2 = now();
            if (distributed::isRoot()) film.setAccumulators(sums);
            whole.push_back(copied + now() - t1);
            reduce.push_back(t2 - t1);
            bytes = double(sums.fixed.size() * sizeof(sums.fixed[0]) + sums.counts.size() * sizeof(int64_t));
            // What the renderer does (renderer.cpp, sumFilmToRoot): 4096 pixels at a time
            // through a small buffer, straight out of the film and back into it.
            distributed::barrier();
            const double t3 = now();
            std::vector<Fixed> fixed;
            std::vector<int64_t> counts;
            const size_t pixels = film.pixelCount();
            for (size_t b = 0; b < pixels; b += 4096) {
                const size_t e = std::min(pixels, b + 4096);
                fixed.resize((e - b) * Film::kPixelSums);
                counts.resize(e - b);
                film.pixelSums(b, e, fixed.data(), counts.data());
                distributed::sumToRoot(fixed);
                distributed::sumToRoot(counts);
                if (distributed::isRoot()) film.setPixelSums(b, e, fixed.data(), counts.data());
            }
            counts = film.otherCounts();
            distributed::sumToRoot(counts);
            if (distributed::isRoot()) film.setOtherCounts(counts);
            chunked.push_back(now() - t3);
        }
        if (distributed::isRoot())
            std::printf("%s\n", nlohmann::json{{"size", n},
                                               {"pixels", (long long)n * n},
                                               {"ranks", distributed::size()},
                                               {"bytes_per_rank", bytes},
                                               {"reduce_first_s", reduce[0]},
                                               {"reduce_best_s", *std::min_element(reduce.begin(), reduce.end())},
                                               {"reduce_median_s", median(reduce)},
                                               {"with_copies_median_s", median(whole)},
                                               {"chunked_best_s", *std::min_element(chunked.begin(), chunked.end())},
                                               {"chunked_median_s", median(chunked)}}
                                    .dump()
                                    .c_str());
    }
    return distributed::finish(0);
}
