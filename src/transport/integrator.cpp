#include "transport/integrator.h"

#include "transport/bdpt.h"
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
    MisHeuristic heuristic = MisHeuristic::Power;
    if (mis == "balance") heuristic = MisHeuristic::Balance;
    else if (mis == "none") heuristic = MisHeuristic::Uniform;
    else if (mis != "power") throw InputError("unknown MIS heuristic \"" + mis + "\" (available: power, balance, none)");
    int maxDepth = scene.settings().maxDepth;
    if (name == "path") return std::make_unique<PathTracer>(scene, maxDepth);
    if (name == "light" || name == "bdpt" || name == "pssmlt" || name == "mmlt" ||
        name == "mlt") {
        if (!scene.camera().hasImportance())
            throw InputError("integrator \"" + name + "\" connects light paths to the lens and needs a perspective camera");
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
        return std::make_unique<BDPTIntegrator>(scene, maxDepth, heuristic);
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
    if (colon == std::string::npos) return name;
    std::string rest;
    std::stringstream in(spec.substr(colon + 1));
    for (std::string item; std::getline(in, item, ',');) {
        if (item.rfind("two-stage=", 0) == 0) {
            char* end = nullptr;
            const std::string value = item.substr(10);
            st.mltTwoStage = std::strtof(value.c_str(), &end);
            if (value.empty() || *end != '\0' || !(st.mltTwoStage >= 0))
                throw InputError("\"" + spec + "\": two-stage needs a fraction >= 0");
        } else if (item.rfind("black-level=", 0) == 0) {
            char* end = nullptr;
            const std::string value = item.substr(12);
            st.mltTwoStageBlackLevel = std::strtof(value.c_str(), &end);
            if (value.empty() || *end != '\0' || !(st.mltTwoStageBlackLevel >= 0))
                throw InputError("\"" + spec + "\": black-level needs a luminance >= 0");
        } else {
            rest += (rest.empty() ? "" : ",") + item;
        }
    }
    if (!rest.empty() && name != "mlt")
        throw InputError("\"" + spec + "\": only mlt takes mutation weights (" + rest + ")");
    st.mltMutations = rest;
    return name;
}

}  // namespace ps
