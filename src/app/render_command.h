// `pathspace render SCENE [options]`.
#pragma once
#include <CLI/CLI.hpp>

#include <string>

#include "app/render_options.h"

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
    RenderArgs args_;
};

}  // namespace ps
