#include "transport/integrator.h"

#include "mc/mis.h"
#include "transport/bdpt.h"
#include "transport/coverage.h"
#include "transport/light_tracer.h"
#include "transport/mlt/mmlt.h"
#include "transport/mlt/pssmlt.h"
#include "transport/mlt/veach/veach_mlt.h"
#include "transport/path_tracer.h"
#include "util/error.h"

#include <cstdlib>
#include <sstream>

namespace ps {

std::unique_ptr<Integrator> createIntegrator(const std::string& name, const Scene& scene, const std::string& mis) {
    const MisWeighting heuristic = mis.empty() ? MisWeighting{} : parseMisWeighting(mis);
    // Light tracing has one technique per path (its splats are unweighted); Veach's mlt has
    // no strategies to weigh: its chains sample paths by f itself (its bootstrap's weights,
    // f over the summed density of every split, are fixed by its start-up, not a choice).
    if (!mis.empty() && (name == "light" || name == "mlt"))
        throw InputError("--mis " + mis + ": integrator \"" + name + "\" combines no sampling techniques by a " +
                         "heuristic (--mis applies to path, bdpt, pssmlt and mmlt)");
    int maxDepth = scene.settings().maxDepth;
    const int lightSamples = scene.settings().lightSamples;
    // Splitting next-event estimation is the path tracer's: BDPT's s = 1 strategy would need
    // its weights against every other strategy recounted, light tracing and the chains have
    // no per-vertex light sample, and volpath's spectral MIS weighs per wavelength.
    if (lightSamples != 1 && (name != "path" || scene.hasMedia()))
        throw InputError("--light-samples " + std::to_string(lightSamples) + ": " +
                         (name != "path" ? "integrator \"" + name + "\" takes no light samples per vertex"
                                         : std::string("in a scene with participating media")) +
                         "; it applies to path in scenes without media");
    if (name == "path") {
        // volpath divides by the densities' mean over wavelengths and techniques: spectral
        // MIS, the balance heuristic (volpath.cpp).
        if (scene.hasMedia() && !mis.empty() && heuristic.heuristic != MisHeuristic::Balance)
            throw InputError("--mis " + mis + ": in a scene with participating media, path weighs light and " +
                             "scattering samples over wavelengths by the balance heuristic (spectral MIS); " +
                             "only --mis balance applies");
        return std::make_unique<PathTracer>(scene, maxDepth, heuristic, lightSamples);
    }
    if (name == "light" || name == "bdpt" || name == "pssmlt" || name == "mmlt" ||
        name == "mlt") {
        // Emission inside media has no strategy in light tracing and mlt: rendered, such a scene
        // would be silently dark (coverage.h, unsupportedMedia).
        if (const std::string why = unsupportedMedia(scene, name); !why.empty()) throw InputError(why);
        // Light tracing and Veach's lens mutations need the camera's importance; BDPT and the
        // primary-sample chains do without its t = 1 strategies.
        if ((name == "light" || name == "mlt") && !scene.camera().hasImportance())
            throw InputError("integrator \"" + name + "\" " + lensRequirement(name));
        if (name == "light") return std::make_unique<LightTracer>(scene, maxDepth);
        if (name == "pssmlt" || name == "mmlt" || name == "mlt") {
            const RenderSettings& st = scene.settings();
            MetropolisParams mp{st.mltBootstrapSamples, st.mltChains, st.mltLargeStepProbability, st.mltSigma,
                                st.mltStrategyPilot};
            mp.cameraStepProbability = st.mltCameraStepProbability;
            mp.twoStage = metropolisTwoStage(name, st.mltTwoStage);
            mp.twoStageBlackLevel = st.mltTwoStageBlackLevel;
            if (name == "mlt")
                return std::make_unique<VeachMLTIntegrator>(scene, maxDepth, mp, parseMutationWeights(st.mltMutations));
            if (name == "mmlt") return std::make_unique<MMLTIntegrator>(scene, maxDepth, mp, heuristic);
            return std::make_unique<PSSMLTIntegrator>(scene, maxDepth, mp, heuristic);
        }
        auto bdpt = std::make_unique<BDPTIntegrator>(scene, maxDepth, heuristic);
        bdpt->setLightPathShare(scene.settings().bdptLightPaths);
        return bdpt;
    }
    throw InputError("unknown integrator \"" + name + "\" (available: path, light, bdpt, pssmlt, mmlt, mlt)");
}

double metropolisTwoStage(const std::string& name, double setting) {
    if (setting >= 0) return setting;
    // Measured at equal time on veach-ajar and door-ajar (bench/README, "Two-stage MLT with a
    // black level"): a pilot of whole BDPT samples as many as the bootstrap's for pssmlt and
    // mmlt; a quarter of them for mlt, whose mutations gain less from a finer map than they
    // lose to its noise and cost.
    return name == "mlt" ? 0.25 : 1.0;
}

std::string applyIntegratorVariant(const std::string& spec, RenderSettings& st) {
    const size_t colon = spec.find(':');
    const std::string name = spec.substr(0, colon);
    const RenderSettings defaults;
    st.mltMutations = defaults.mltMutations;
    st.mltTwoStage = defaults.mltTwoStage;
    st.mltTwoStageBlackLevel = defaults.mltTwoStageBlackLevel;
    st.bdptLightPaths = defaults.bdptLightPaths;
    if (colon == std::string::npos) return name;
    std::string rest;
    std::stringstream in(spec.substr(colon + 1));
    // Two-stage MLT's keys, each a number >= 0; the rest are mlt's mutation weights.
    struct Key {
        std::string name;
        float* value;
        const char* what;
    };
    const Key keys[] = {{"two-stage", &st.mltTwoStage, "a fraction"},
                        {"black-level", &st.mltTwoStageBlackLevel, "a luminance"},
                        {"light-paths", &st.bdptLightPaths, "a share"}};
    for (std::string item; std::getline(in, item, ',');) {
        const Key* key = nullptr;
        for (const Key& k : keys)
            if (item.rfind(k.name + "=", 0) == 0) key = &k;
        if (!key) {
            rest += (rest.empty() ? "" : ",") + item;
            continue;
        }
        char* end = nullptr;
        const std::string value = item.substr(key->name.size() + 1);
        *key->value = std::strtof(value.c_str(), &end);
        if (value.empty() || *end != '\0' || !(*key->value >= 0))
            throw InputError("\"" + spec + "\": " + key->name + " needs " + key->what + " >= 0");
    }
    if (!(st.bdptLightPaths > 0 && st.bdptLightPaths <= 1) || (st.bdptLightPaths != 1 && name != "bdpt"))
        throw InputError("\"" + spec + "\": light-paths is BDPT's, a share in (0, 1]");
    if (!rest.empty() && name != "mlt")
        throw InputError("\"" + spec + "\": only mlt takes mutation weights (" + rest + ")");
    st.mltMutations = rest;
    return name;
}

}  // namespace ps
