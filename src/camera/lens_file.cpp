#include "camera/lens_file.h"

#include <cerrno>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>

#include "util/error.h"
#include "util/input_files.h"

namespace ps {

namespace {

struct Number {
    float value;
    int line;
};

// Splits the text into numbers, skipping '#' comments, remembering each number's line.
std::vector<Number> tokenize(const std::string& text, const std::string& name) {
    std::vector<Number> out;
    int line = 1;
    size_t i = 0;
    while (i < text.size()) {
        char c = text[i];
        if (c == '\n') {
            ++line;
            ++i;
        } else if (c == '#') {
            while (i < text.size() && text[i] != '\n') ++i;
        } else if (std::isspace(static_cast<unsigned char>(c))) {
            ++i;
        } else {
            size_t end = i;
            while (end < text.size() && !std::isspace(static_cast<unsigned char>(text[end])) && text[end] != '#') ++end;
            std::string word = text.substr(i, end - i);
            char* stop = nullptr;
            errno = 0;
            float v = std::strtof(word.c_str(), &stop);
            if (word.empty() || stop != word.c_str() + word.size())
                throw InputError(name + ":" + std::to_string(line) + ": lens description: " + quoteForMessage(word) +
                                 " is not a number");
            if (!std::isfinite(v))
                throw InputError(name + ":" + std::to_string(line) + ": lens description: " + quoteForMessage(word) +
                                 " is not a finite number");
            out.push_back({v, line});
            i = end;
        }
    }
    return out;
}

}  // namespace

std::vector<LensInterface> parseLensDescription(const std::string& text, const std::string& name) {
    std::vector<Number> nums = tokenize(text, name);
    if (nums.empty()) throw InputError(name + ": lens description has no interfaces");
    if (nums.size() % 4 != 0) {
        const Number& first = nums[nums.size() / 4 * 4];
        throw InputError(name + ":" + std::to_string(first.line) + ": lens description: " + std::to_string(nums.size()) +
                         " numbers, not a multiple of four (radius, thickness, index, aperture diameter per interface); "
                         "this row is incomplete");
    }
    std::vector<LensInterface> lens;
    for (size_t k = 0; k < nums.size(); k += 4) {
        const int line = nums[k].line;
        auto bad = [&](const std::string& what) {
            return InputError(name + ":" + std::to_string(line) + ": lens description: " + what);
        };
        LensInterface e;
        e.curvatureRadius = nums[k].value / 1000;
        e.thickness = nums[k + 1].value / 1000;
        e.eta = nums[k + 2].value == 0 ? 1.0f : nums[k + 2].value;
        e.apertureRadius = nums[k + 3].value / 2000;
        if (nums[k + 1].value < 0) throw bad("negative thickness");
        if (nums[k + 2].value < 0) throw bad("negative index of refraction");
        if (!(nums[k + 3].value > 0)) throw bad("the aperture diameter must be positive");
        lens.push_back(e);
    }
    return lens;
}

std::vector<LensInterface> readLensFile(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(path + ": cannot open lens file: " + std::strerror(errno));
    noteInputFile(path);
    std::ostringstream ss;
    ss << in.rdbuf();
    return parseLensDescription(ss.str(), path);
}

}  // namespace ps
