#include "verify/verify.h"

#include <algorithm>
#include <cstdlib>

#include "transport/coverage.h"
#include "transport/integrator.h"
#include "transport/renderer.h"

namespace ps::verify {

const std::vector<std::string>& allIntegrators() {
    static const std::vector<std::string> names{"path", "light", "bdpt", "pssmlt", "mmlt", "mlt"};
    return names;
}

bool VerifyReport::allAgree() const {
    for (const IntegratorResult& r : results)
        if (r.skipped.empty() && (!r.compared || !r.verdict.agrees)) return false;
    return comparedCount() > 0 && !interrupted;
}

int VerifyReport::comparedCount() const {
    int n = 0;
    for (const IntegratorResult& r : results) n += r.compared;
    return n;
}

namespace {

// PATHSPACE_VERIFY_BREAK=NAME:FACTOR multiplies NAME's images by FACTOR: a deliberately
// broken integrator, so that verify's own tests (and a doubting user) can watch it catch one.
double breakFactor(const std::string& name) {
    const char* spec = std::getenv("PATHSPACE_VERIFY_BREAK");
    if (!spec) return 1;
    const std::string s(spec);
    const size_t colon = s.find(':');
    if (colon == std::string::npos || s.substr(0, colon) != name) return 1;
    const double f = std::atof(s.c_str() + colon + 1);
    return f > 0 ? f : 1;
}

void renderRuns(Scene& scene, const VerifyOptions& o, int integratorsToRun, IntegratorResult& r) {
    RenderSettings& st = scene.settings();
    const RenderSettings before = st;
    st.integrator = r.name;
    if (o.configure) o.configure(r.name, st);
    auto integrator = createIntegrator(r.name, scene);
    struct Restore {
        RenderSettings& st;
        const RenderSettings& before;
        ~Restore() { st = before; }
    } restore{st, before};
    for (int k = 0; k < o.runs; ++k) {
        if (o.cancel && o.cancel->load()) return;
        if (o.onRun) o.onRun(r.name, k, o.runs);
        RenderOptions ro;
        auto own = o.sppOf.find(r.name);
        ro.spp = own != o.sppOf.end() ? own->second : o.spp;
        if (o.seconds > 0) {
            ro.timeLimit = o.seconds / (double(integratorsToRun) * o.runs);
            ro.spp = 1 << 20;  // the time decides
        }
        ro.seed = o.seed + uint64_t(k);
        ro.threads = o.threads;
        ro.sampler = st.sampler;
        ro.progress = false;
        ro.cancel = o.cancel;
        ro.errorEstimate = ro.varianceImage = ro.pixelSamples = false;
        RenderResult res = render(scene, *integrator, ro);
        if (o.cancel && o.cancel->load()) return;  // a run cut short is not a whole estimate
        if (const double f = breakFactor(r.name); f != 1)
            for (float& c : res.image.rgb) c *= float(f);
        r.runs.add(res.image);
        r.seconds += res.seconds;
        r.meanSpp += res.meanSpp / o.runs;
    }
}

// Without a reference, each is compared with the others that agree with one another: the
// largest group whose every pair agrees, as a bit set over `rendered` (a broken estimator
// among three would otherwise move the reference of the two good ones, and be hidden by them
// in turn).
unsigned largestAgreeingGroup(const std::vector<IntegratorResult*>& rendered, double blockFloor) {
    const size_t n = rendered.size();
    std::vector<std::vector<bool>> agree(n, std::vector<bool>(n, true));
    for (size_t i = 0; i < n; ++i)
        for (size_t j = 0; j < i; ++j)
            agree[i][j] = agree[j][i] =
                compare(rendered[i]->runs, referenceFrom(rendered[j]->runs, ""), blockFloor).agrees &&
                compare(rendered[j]->runs, referenceFrom(rendered[i]->runs, ""), blockFloor).agrees;
    unsigned best = 0;
    for (unsigned set = 1; set < (1u << n) && n <= 16; ++set) {
        bool clique = true;
        for (size_t i = 0; i < n && clique; ++i)
            for (size_t j = 0; j < i && clique; ++j)
                if ((set >> i & 1) && (set >> j & 1) && !agree[i][j]) clique = false;
        if (clique && __builtin_popcount(set) > __builtin_popcount(best)) best = set;
    }
    return best;
}

}  // namespace

VerifyReport verifyScene(Scene& scene, const VerifyOptions& o, const Reference* reference) {
    VerifyReport report;
    const std::vector<std::string>& names = o.integrators.empty() ? allIntegrators() : o.integrators;
    int toRun = 0;
    for (const std::string& name : names) {
        IntegratorResult r;
        r.name = name;
        r.runs = RunSet(o.blocksX, o.blocksY);
        r.skipped = unsupportedMedia(scene, name);
        if (r.skipped.empty()) r.skipped = missingPaths(scene, name);
        if (r.skipped.empty()) r.skipped = inconsistentSurfaces(scene, name);
        toRun += r.skipped.empty();
        report.results.push_back(std::move(r));
    }
    for (IntegratorResult& r : report.results) {
        if (!r.skipped.empty()) continue;
        renderRuns(scene, o, toRun, r);
        if (r.runs.runs() < o.runs) {
            report.interrupted = true;
            return report;
        }
    }
    std::vector<IntegratorResult*> rendered;
    for (IntegratorResult& r : report.results)
        if (r.skipped.empty() && r.runs.runs() >= 2) rendered.push_back(&r);
    const size_t n = rendered.size();
    const unsigned best = reference ? 0 : largestAgreeingGroup(rendered, o.blockFloor);
    for (size_t i = 0; i < n; ++i) {
        IntegratorResult& r = *rendered[i];
        Reference ref;
        if (reference) {
            ref = *reference;
        } else {
            std::vector<const RunSet*> others;
            std::string who;
            for (int pass = 0; pass < 2 && others.empty(); ++pass)  // the group, else everyone else
                for (size_t j = 0; j < n; ++j)
                    if (j != i && (pass == 1 || (best >> j & 1))) {
                        others.push_back(&rendered[j]->runs);
                        who += (who.empty() ? "" : ", ") + rendered[j]->name;
                    }
            if (others.empty()) continue;
            ref = pooledOf(others, others.size() == 1 ? who : "the pooled " + who);
        }
        r.reference = ref.what;
        r.verdict = compare(r.runs, ref, o.blockFloor);
        r.compared = true;
    }
    return report;
}

}  // namespace ps::verify
