// What the command line accepts beyond CLI11's own rules: pbrt-v4's spellings, help that fits
// a terminal, and values that are never options.
#pragma once
#include <CLI/CLI.hpp>

#include <string>
#include <vector>

namespace ps {

// The arguments as CLI11 should read them (without the program name). pbrt-v4's habits become
// ours: `pathspace scene.pbrt [options]` is `pathspace render ...`; `--stats` with no file
// after it (pbrt-v4's flag) prints the statistics; `--crop x0,x1,y0,y1` is the four values.
std::vector<std::string> normaliseArguments(int argc, char** argv);

// Help text wrapped at 100 columns, each option's description beside it.
std::shared_ptr<CLI::Formatter> wrappingFormatter();

// Every option of `cmd` that takes a value refuses one that looks like an option ("--stats
// --quiet" would otherwise write the statistics to a file named "--quiet"). Negative numbers
// still pass, for the checks that explain their range.
void refuseOptionsAsValues(CLI::App* cmd);

}  // namespace ps
