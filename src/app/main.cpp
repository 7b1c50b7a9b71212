// The pathspace command line.
#include <CLI/CLI.hpp>

#include <csignal>
#include <cstdio>
#include <iostream>

#include "app/exit_codes.h"
#include "app/mc_command.h"
#include "app/render_command.h"
#include "util/error.h"

int main(int argc, char** argv) {
    CLI::App app{"pathspace: a physically based renderer (Veach's robust Monte Carlo light transport).\n"
                 "Exit status: 0 success, 1 internal error, 2 bad input, 130 interrupted (image so far written)."};
    app.require_subcommand(1);
    ps::RenderCommand render;
    render.attach(app);
    ps::McCommand mc;
    mc.attach(app);
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        int code = app.exit(e);
        return code == 0 ? ps::kExitOk : ps::kExitBadInput;
    }
    try {
        return mc.parsed() ? mc.run() : render.run();
    } catch (const ps::InputError& e) {
        std::fprintf(stderr, "%s\n", ps::printableMessage(e.what()).c_str());
        return ps::kExitBadInput;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "internal error: %s\n", ps::printableMessage(e.what()).c_str());
        return ps::kExitInternalError;
    }
}
