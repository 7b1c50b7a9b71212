// The pathspace command line.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <exception>
#include <iostream>
#include <thread>

#include "app/command_line.h"
#include "app/exit_codes.h"
#include "app/mc_command.h"
#include "app/render_command.h"
#include "app/verify_command.h"
#include "render/distributed.h"
#include "util/error.h"

namespace {

// Says what went wrong, for a failure met where the processes do not agree on it first (input
// errors before the render do: distributed::failedEverywhere). In a job of several processes
// it ends the job (finish). Rank 0 reports at once; another rank first waits a moment, in
// which rank 0's report of the same error ends the job, so only a failure of its own is
// reported (with its rank).
void report(const char* prefix, const char* what) {
    const int rank = ps::distributed::rank();
    if (rank != 0) std::this_thread::sleep_for(std::chrono::seconds(2));
    std::string where = rank != 0 ? "rank " + std::to_string(rank) + ": " : "";
    std::fprintf(stderr, "%s%s%s\n", where.c_str(), prefix, ps::printableMessage(what).c_str());
}

}  // namespace

int main(int argc, char** argv) {
    ps::distributed::start(argc, argv);
    // One voice per job: rank 0 prints warnings; the others keep theirs for rank 0 to print
    // those it did not meet itself (RenderCommand).
    if (!ps::distributed::isRoot()) ps::setWarningsQuiet(true);
    CLI::App app{"pathspace: a physically based renderer (Veach's robust Monte Carlo light transport).\n"
                 "`pathspace SCENE.pbrt [options]` is `pathspace render SCENE.pbrt [options]`.\n"
                 "Exit status: 0 success, 1 internal error, 2 bad input, 3 verify found a disagreement,\n"
                 "130 interrupted (image so far written)."};
    app.name("pathspace");
    app.require_subcommand(1);
    app.formatter(ps::wrappingFormatter());
    app.set_version_flag("--version", std::string("pathspace ") + PATHSPACE_VERSION);
    ps::RenderCommand render;
    render.attach(app);
    ps::McCommand mc;
    mc.attach(app);
    ps::VerifyCommand verify;
    verify.attach(app);
    // The command line is every process's: an error in it (or --help) is met by all, and rank
    // 0 alone prints it (distributed::failedEverywhere: if only some met it, the job aborts).
    std::exception_ptr parseError;
    std::string parseMessage;
    try {
        // CLI11 reads a vector of arguments last to first.
        std::vector<std::string> args = ps::normaliseArguments(argc, argv);
        std::reverse(args.begin(), args.end());
        app.parse(args);
    } catch (const CLI::ParseError& e) {
        parseError = std::current_exception();
        parseMessage = e.what();
    }
    if (ps::distributed::failedEverywhere(bool(parseError), parseMessage, ps::kExitBadInput)) {
        try {
            std::rethrow_exception(parseError);
        } catch (const CLI::ParseError& e) {
            const int code = ps::distributed::isRoot() ? app.exit(e) : e.get_exit_code();
            return ps::distributed::finish(code == 0 ? ps::kExitOk : ps::kExitBadInput, true);
        }
    }
    try {
        if ((mc.parsed() || verify.parsed()) && ps::distributed::size() > 1)
            throw ps::distributed::JobInputError(std::string(mc.parsed() ? "mc" : "verify") +
                                                 " runs in one process: start it without mpirun");
        if (verify.parsed()) return ps::distributed::finish(verify.run());
        return ps::distributed::finish(mc.parsed() ? mc.run() : render.run());
    } catch (const ps::distributed::JobInputError& e) {
        // Raised by every process at once: one report, and no process aborts the others.
        if (ps::distributed::isRoot()) std::fprintf(stderr, "%s\n", ps::printableMessage(e.what()).c_str());
        return ps::distributed::finish(ps::kExitBadInput, true);
    } catch (const ps::InputError& e) {
        report("", e.what());
        return ps::distributed::finish(ps::kExitBadInput);
    } catch (const std::exception& e) {
        report("internal error: ", e.what());
        return ps::distributed::finish(ps::kExitInternalError);
    }
}
