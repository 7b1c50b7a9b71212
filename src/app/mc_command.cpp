#include "app/mc_command.h"

#include "app/command_line.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>

#include "app/exit_codes.h"
#include "app/svg_plot.h"
#include "mc/convergence.h"
#include "mc/mis_study.h"
#include "mc/techniques.h"
#include "mc/test_integrands.h"
#include "util/error.h"

namespace ps {

namespace {

std::string joined(const std::vector<std::string>& names) {
    std::string s;
    for (const std::string& n : names) s += (s.empty() ? "" : ", ") + n;
    return s;
}

std::vector<std::string> techniqueNames() {
    std::vector<std::string> names;
    for (const Technique& t : techniques()) names.push_back(t.name);
    return names;
}

// "all" expands to every known name; anything unknown is bad input.
std::vector<std::string> expand(const std::vector<std::string>& asked, const std::vector<std::string>& known,
                                const char* what) {
    std::vector<std::string> out;
    for (const std::string& a : asked) {
        if (a == "all") return known;
        if (std::find(known.begin(), known.end(), a) == known.end())
            throw InputError(std::string("unknown ") + what + " \"" + a + "\" (known: " + joined(known) + ", all)");
        out.push_back(a);
    }
    return out;
}

std::string fmt(const char* f, double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, f, v);
    return buf;
}

// FNV-1a: a stable hash of a name, so a seed gives the same numbers on every platform
// (std::hash is implementation-defined).
uint64_t nameHash(const std::string& s) {
    uint64_t h = 0xcbf29ce484222325ULL;
    for (unsigned char c : s) h = (h ^ c) * 0x100000001b3ULL;
    return h;
}

void writeFile(const std::string& path, const std::string& text) {
    std::ofstream out(path, std::ios::binary);
    out << text;
    out.close();
    if (!out) throw InputError("cannot write \"" + path + "\"");
}

}  // namespace

nlohmann::json convergencePointJson(const ConvergencePoint& p) {
    return {{"n", p.n},
            {"evaluations", p.evaluations},
            {"mean", p.mean},
            {"standard_error", p.standardError},
            {"reported_error", p.reportedError},
            {"rmse", p.rmse},
            {"seconds", p.seconds},
            {"efficiency", p.efficiency}};
}

void McCommand::attach(CLI::App& app) {
    cmd_ = app.add_subcommand("mc", "Monte Carlo toolbox (thesis ch. 2): compare estimators on test integrands "
                                    "with known integrals");
    cmd_->add_option("--integrand", integrands_, "Test integrand(s): " + joined(testIntegrandNames()) + ", or all")
        ->capture_default_str();
    cmd_->add_option("--dims", dims_, "Dimension(s) s of the integration domain [0,1)^s, 1 to 10")
        ->check(CLI::Range(1, kTestIntegrandMaxDims))
        ->capture_default_str();
    cmd_->add_option("--technique", techniques_, "Technique(s): " + joined(techniqueNames()) + ", or all")
        ->capture_default_str();
    nOption_ = cmd_->add_option("--n", ns_, "Sample counts N (integrand evaluations per run, at least 16); the table shows the "
                                 "largest, the slope is fitted over all")
        ->check(CLI::Range(16, 1 << 24))
        ->capture_default_str();
    cmd_->add_option("--runs", runs_, "Independent runs R per N (RMSE and standard error are measured over them)")
        ->check(CLI::Range(2, 100000))
        ->capture_default_str();
    cmd_->add_option("--seed", seed_, "Random seed (same seed, same numbers)")->capture_default_str();
    cmd_->add_option("--json", jsonFile_, "Write every measurement as JSON to this file");
    cmd_->add_option("--svg", svgFile_, "Write a log-log plot of RMSE against N (one panel per integrand and "
                                        "dimension, one line per technique) as SVG to this file");
    cmd_->add_option("--study", study_,
                     "mis: compare the MIS heuristics of thesis ch. 9 (balance, power, cutoff, maximum, and each "
                     "technique alone) on Veach's glossy highlights, by variance and efficiency; --n sets the "
                     "estimates per case (default 200000), --seed and --json apply")
        ->check(CLI::IsMember({"mis"}));
    refuseOptionsAsValues(cmd_);
}

int McCommand::run() {
    if (study_ == "mis") return runMisStudy();
    std::vector<std::string> integrands = expand(integrands_, testIntegrandNames(), "integrand");
    std::vector<std::string> names = expand(techniques_, techniqueNames(), "technique");
    std::vector<int> ns = ns_;
    std::sort(ns.begin(), ns.end());
    ns.erase(std::unique(ns.begin(), ns.end()), ns.end());

    nlohmann::json results = nlohmann::json::array();
    std::vector<PlotPanel> panels;
    std::printf("pathspace mc: %d runs per N, N = %d..%d, seed %llu. Columns at the largest N: estimate = mean "
                "of the runs, std. error and rel. RMSE = one run's, efficiency = 1/(V T) per run.\n",
                runs_, ns.front(), ns.back(), (unsigned long long)seed_);
    for (const std::string& name : integrands) {
        for (int dims : dims_) {
            TestIntegrand t = makeTestIntegrand(name, dims);
            std::printf("\n%s, s = %d: %s, exact %.10g\n\n", t.name.c_str(), dims, t.description.c_str(), t.exact);
            std::printf("| technique | evaluations | estimate | std. error | rel. RMSE | time/run | efficiency | slope |\n");
            std::printf("|---|---:|---:|---:|---:|---:|---:|---:|\n");
            nlohmann::json jt = nlohmann::json::array();
            PlotPanel panel{t.name + ", s = " + std::to_string(dims), "integrand evaluations", "RMSE", {}};
            for (const std::string& tn : names) {
                const Technique& tech = *findTechnique(tn);
                if (!tech.applies(t)) continue;
                // Each (integrand, dims, technique) has its own streams: adding a technique to the
                // list does not change the others' numbers.
                uint64_t key = hashCombine(hashCombine(hashCombine(seed_, nameHash(t.name)), uint64_t(dims)),
                                           nameHash(tech.name));
                ConvergenceStudy study = studyConvergence(
                    [&](int n, Rng& rng) { return tech.run(t, n, rng); }, t.exact, ns, runs_, key);
                const ConvergencePoint& last = study.points.back();
                std::printf("| %s | %.0f | %s | %s | %s | %s | %s | %s |\n", tech.name.c_str(), last.evaluations,
                            fmt("%.6g", last.mean).c_str(), fmt("%.3g", last.standardError).c_str(),
                            fmt("%.3g", last.rmse / std::abs(t.exact)).c_str(),
                            fmt("%.3g ms", last.seconds * 1e3).c_str(), fmt("%.3g", last.efficiency).c_str(),
                            fmt("%.2f", study.slope).c_str());
                std::fflush(stdout);
                nlohmann::json pts = nlohmann::json::array();
                PlotSeries series{tech.name, {}, {}};
                for (const ConvergencePoint& p : study.points) {
                    pts.push_back(convergencePointJson(p));
                    series.x.push_back(p.evaluations);
                    series.y.push_back(p.rmse);
                }
                jt.push_back({{"name", tech.name},
                              {"description", tech.description},
                              {"slope", std::isfinite(study.slope) ? nlohmann::json(study.slope) : nlohmann::json()},
                              {"points", pts}});
                panel.series.push_back(std::move(series));
            }
            results.push_back({{"integrand", t.name},
                               {"description", t.description},
                               {"dims", dims},
                               {"exact", t.exact},
                               {"techniques", jt}});
            panels.push_back(std::move(panel));
        }
    }
    if (!jsonFile_.empty()) {
        nlohmann::json j{{"seed", seed_}, {"runs", runs_}, {"n", ns}, {"results", results}};
        writeFile(jsonFile_, j.dump(2) + "\n");
    }
    if (!svgFile_.empty()) writeFile(svgFile_, logLogPlotSvg(panels, 2));
    return kExitOk;
}

// Thesis ch. 9's comparison, figs. 9.2 and 9.3: for every light size and lobe, each
// strategy's variance of one estimate (two samples), relative to the integral squared, and
// its efficiency 1/(V T); then how far each strategy is from the best in each case.
int McCommand::runMisStudy() {
    const int samples = nOption_->count() > 0 ? *std::max_element(ns_.begin(), ns_.end()) : 200000;
    const std::vector<MisStrategy> strategies = misStudyStrategies();
    const std::vector<MisStudyCell> cells = ps::runMisStudy(strategies, samples, seed_);
    std::printf("pathspace mc --study mis: Veach's glossy highlights (thesis figs. 9.2, 9.3): a spherical light of "
                "angular radius r seen in a Phong lobe of exponent n, the mirror direction r/2 from the light's "
                "centre; one light and one BSDF sample per estimate, combined by each heuristic (or two samples "
                "of one technique). %d estimates per case, seed %llu.\n",
                samples, (unsigned long long)seed_);
    auto header = [&](const char* what) {
        std::printf("\n%s\n\n| light r | exponent n | integral |", what);
        for (const MisStrategy& st : strategies) std::printf(" %s |", st.name.c_str());
        std::printf("\n|---:|---:|---:|");
        for (size_t i = 0; i < strategies.size(); ++i) std::printf("---:|");
        std::printf("\n");
    };
    header("Relative variance V / I^2 of one estimate (lower is better; * the lowest):");
    // Theorem 9.2 bounds the balance heuristic's variance by any other weighting's plus
    // (1/min n_i - 1/sum n_i) I^2, I^2 / 2 here: the excess over the best is additive.
    std::vector<double> excess(strategies.size(), 0), bias(strategies.size(), 0);
    std::vector<int> nearBest(strategies.size(), 0);
    for (const MisStudyCell& c : cells) {
        const double best = *std::min_element(c.variance.begin(), c.variance.end());
        const double I2 = c.exact * c.exact;
        double bestHeuristic = 1e300;  // among the combinations alone
        for (size_t i = 0; i < strategies.size(); ++i)
            if (strategies[i].alone < 0) bestHeuristic = std::min(bestHeuristic, c.variance[i]);
        std::printf("| %g | %g | %.6g |", c.setup.lightRadius, c.setup.exponent, c.exact);
        for (size_t i = 0; i < strategies.size(); ++i) {
            std::printf(" %s%s |", fmt("%.3g", c.variance[i] / I2).c_str(), c.variance[i] == best ? "*" : "");
            excess[i] = std::max(excess[i], (c.variance[i] - best) / I2);
            nearBest[i] += strategies[i].alone < 0 && c.variance[i] == bestHeuristic;
            const double sigma = std::sqrt(c.variance[i] / samples);
            if (sigma > 0) bias[i] = std::max(bias[i], std::abs(c.mean[i] - c.exact) / sigma);
        }
        std::printf("\n");
    }
    header("Efficiency 1 / (V T) per second, V relative (higher is better):");
    for (const MisStudyCell& c : cells) {
        std::printf("| %g | %g | %.6g |", c.setup.lightRadius, c.setup.exponent, c.exact);
        for (size_t i = 0; i < strategies.size(); ++i) {
            const double v = c.variance[i] / (c.exact * c.exact), t = c.seconds[i] / samples;
            std::printf(" %s |", v > 0 ? fmt("%.3g", 1 / (v * t)).c_str() : "inf");
        }
        std::printf("\n");
    }
    std::printf("\nAcross the %zu cases: the largest excess of variance over the best strategy's, (V - V_best) / "
                "I^2 (Theorem 9.2: at most 1/2 for balance), the cases where it is the best heuristic, and the largest "
                "|mean - integral| in standard errors (unbiased: a few at most).\n\n"
                "| strategy | largest (V - V_best) / I^2 | best heuristic in | largest bias / sigma |\n"
                "|---|---:|---:|---:|\n",
                cells.size());
    for (size_t i = 0; i < strategies.size(); ++i)
        std::printf("| %s | %s | %s | %.2f |\n", strategies[i].name.c_str(), fmt("%.3g", excess[i]).c_str(),
                    strategies[i].alone < 0 ? std::to_string(nearBest[i]).c_str() : "-", bias[i]);
    if (!jsonFile_.empty()) {
        nlohmann::json jc = nlohmann::json::array();
        for (const MisStudyCell& c : cells) {
            nlohmann::json per = nlohmann::json::object();
            for (size_t i = 0; i < strategies.size(); ++i)
                per[strategies[i].name] = {{"mean", c.mean[i]}, {"variance", c.variance[i]}, {"seconds", c.seconds[i]}};
            jc.push_back({{"light_radius", c.setup.lightRadius},
                          {"offset", c.setup.offset},
                          {"exponent", c.setup.exponent},
                          {"integral", c.exact},
                          {"strategies", per}});
        }
        nlohmann::json j{{"study", "mis"}, {"seed", seed_}, {"samples", samples}, {"cases", jc}};
        writeFile(jsonFile_, j.dump(2) + "\n");
    }
    return kExitOk;
}

}  // namespace ps
