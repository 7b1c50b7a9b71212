// `pathspace render SCENE [options]`.
#pragma once
#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace ps {

struct CheckpointState;  // transport/checkpoint.h

class RenderCommand {
public:
    void attach(CLI::App& app);
    int run();  // exit status

private:
    struct Job;
    // Reads the scene and applies the options (every process alike; throws InputError).
    void load(Job& job);
    // Rank 0's checks of the files it alone writes or reads (outputs, checkpoints).
    void checkRootsFiles(const Job& job, CheckpointState& resumed);

    CLI::App* cmd_ = nullptr;
    std::string scene_;
    int spp_ = 0;
    double time_ = 0;
    int threads_ = 0;
    long long seed_ = -1;
    int maxDepth_ = -1;
    std::string integrator_;
    std::string mis_ = "power";
    std::string strategiesDir_;
    std::string sampler_;
    std::string color_ = "spectral";
    std::string adaptive_;
    std::vector<std::string> aovs_;
    std::vector<std::string> outputs_;
    std::vector<float> crop_;
    std::vector<int> pixelBounds_;  // --pixelbounds x0 x1 y0 y1
    std::string statsFile_;
    bool statsPrint_ = false;  // `--stats` without a file
    std::string checkpoint_, resume_;  // --checkpoint FILE, --resume FILE
    double checkpointEvery_ = -1;      // --checkpoint-every SECONDS
    std::string maxMemory_;
    // Metropolis parameters (override the scene's Integrator "pssmlt"/"mlt" ones); unset when < 0.
    int chains_ = -1;
    int bootstrap_ = -1;
    double largeStepProbability_ = -1;
    double cameraStepProbability_ = -1;
    double strategyPilot_ = -1;
    double twoStage_ = -1;
    double twoStageBlackLevel_ = -1;
    double sigma_ = -1;
    int mltDirect_ = -1;        // --mlt-direct N
    std::string mltMutations_;  // --mlt-mutations KEY=VALUE,...  // --max-memory SIZE, checked by parseByteSize
    bool quiet_ = false;
};

}  // namespace ps
