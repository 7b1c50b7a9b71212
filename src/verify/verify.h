// `pathspace verify`: render one scene with every integrator that can sample it, several
// independent times each, and compare each with the others block by block
// (block_statistics.h). The thesis' case for unbiased estimators is that their only error is
// variance, which can be measured: estimators that differ by more than it allows show a bug,
// or light that one of them cannot sample (transport/coverage.h leaves those out first).
#pragma once
#include <atomic>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "render/scene.h"
#include "verify/block_statistics.h"

namespace ps::verify {

// Every unbiased integrator, in the order reports list them.
const std::vector<std::string>& allIntegrators();

struct VerifyOptions {
    std::vector<std::string> integrators;  // empty: allIntegrators()
    int runs = 8;                          // independent renders of each integrator
    // Either a budget in seconds for the whole verification, split evenly among the
    // integrators and their runs (Metropolis bootstraps included), or samples per pixel
    // (mutations for Metropolis) of each run when seconds is 0.
    double seconds = 0;
    int spp = 16;
    std::map<std::string, int> sppOf;  // per-integrator spp, where one needs other than `spp`
    int threads = 0;
    uint64_t seed = 1;  // run k of every integrator uses seed + k
    int blocksX = 4, blocksY = 4;
    double blockFloor = 0.01;  // see compare()
    const std::atomic<bool>* cancel = nullptr;
    std::function<void(const std::string& integrator, int run, int runs)> onRun;  // before each render
    // Changes to the scene's settings for one integrator (a Metropolis bootstrap, say), made
    // before its renders and undone after them.
    std::function<void(const std::string& integrator, RenderSettings&)> configure;
};

struct IntegratorResult {
    std::string name;
    std::string skipped;  // why it was not rendered, "" when it was
    RunSet runs;
    double seconds = 0;   // all its renders
    double meanSpp = 0;   // per run, averaged
    bool compared = false;
    std::string reference;  // what it was compared with
    Verdict verdict;
};

struct VerifyReport {
    std::vector<IntegratorResult> results;
    bool interrupted = false;
    // Every rendered integrator was compared and agrees.
    bool allAgree() const;
    int comparedCount() const;
};

// Renders the scene with each integrator (its settings' integrator is changed for each and
// restored). Each is compared with `reference` when given (an exact answer, or the scene
// without a feature that must not change it), else with the pooled estimate of the others in
// the largest group that agree pairwise: one that disagrees stands out without trusting any
// single one.
VerifyReport verifyScene(Scene& scene, const VerifyOptions& options, const Reference* reference = nullptr);

}  // namespace ps::verify
