// `pathspace verify SCENE`: renders the scene with every integrator that can sample it and
// says which agree, which differ, where and by how many standard errors (verify/verify.h),
// with a PNG map of the differences and a JSON report. Exit status 0 when all agree.
#pragma once
#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace ps {

// Exit status of a verification whose integrators disagree (or could not be compared).
constexpr int kExitDisagree = 3;

class VerifyCommand {
public:
    void attach(CLI::App& app);
    bool parsed() const { return cmd_ && cmd_->parsed(); }
    int run();  // exit status

private:
    CLI::App* cmd_ = nullptr;
    std::string scene_;
    double time_ = 60;
    int spp_ = 0;
    int runs_ = 12;
    int blocks_ = 4;
    int threads_ = 0;
    long long seed_ = 1;
    int maxDepth_ = -1;
    double twoStage_ = 0;
    std::string color_ = "spectral";
    std::vector<std::string> integrators_;
    std::string map_, json_;
    bool quiet_ = false;
};

}  // namespace ps
