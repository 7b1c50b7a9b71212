// `pathspace mc`: the Monte Carlo toolbox on test integrands with known integrals. For each
// integrand and dimension, every technique runs R times at each sample count N; the table
// shows the largest N and the convergence rate fitted over all of them. `--study mis`
// compares the MIS heuristics of ch. 9 on Veach's glossy highlights instead.
#pragma once
#include <CLI/CLI.hpp>
#include <nlohmann/json_fwd.hpp>
#include <cstdint>
#include <string>
#include <vector>

namespace ps {

struct ConvergencePoint;

// One sample count's measurements as --json writes them (also pathspace.mc.convergence's).
nlohmann::json convergencePointJson(const ConvergencePoint& p);

class McCommand {
public:
    void attach(CLI::App& app);
    bool parsed() const { return cmd_ && cmd_->parsed(); }
    int run();  // exit status

private:
    int runMisStudy();  // --study mis

    CLI::App* cmd_ = nullptr;
    std::vector<std::string> integrands_{"all"};
    std::vector<int> dims_{2, 6};
    std::vector<std::string> techniques_{"all"};
    std::vector<int> ns_{64, 256, 1024, 4096, 16384};
    int runs_ = 32;
    uint64_t seed_ = 1;
    std::string jsonFile_, svgFile_;
    std::string study_;  // "mis": the MIS heuristics' study instead of the integrands
    CLI::Option* nOption_ = nullptr;
};

}  // namespace ps
