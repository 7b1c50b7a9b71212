#include "app/command_line.h"

#include <cstdlib>
#include <sstream>

namespace ps {

namespace {

bool endsWith(const std::string& s, const std::string& tail) {
    return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

bool isSceneFile(const std::string& s) { return endsWith(s, ".pbrt") || endsWith(s, ".pbrt.gz"); }

bool looksLikeNumber(const std::string& s) {
    char* end = nullptr;
    std::strtod(s.c_str(), &end);
    return end != s.c_str() && *end == '\0';
}

bool looksLikeOption(const std::string& s) { return s.size() > 1 && s[0] == '-' && !looksLikeNumber(s); }

// Words of `text` on lines of at most `width` characters (a longer word has a line alone).
std::string wrap(const std::string& text, size_t width) {
    std::istringstream in(text);
    std::string word, out, line;
    while (in >> word) {
        if (!line.empty() && line.size() + 1 + word.size() > width) {
            out += line + "\n";
            line.clear();
        }
        line += (line.empty() ? "" : " ") + word;
    }
    return out + line;
}

class WrappingFormatter : public CLI::Formatter {
public:
    WrappingFormatter() { column_width(kNameColumn); }
    std::string make_option_desc(const CLI::Option* opt) const override {
        return wrap(CLI::Formatter::make_option_desc(opt), kWidth - kNameColumn);
    }
    std::string make_subcommand(const CLI::App* sub) const override {
        std::stringstream out;
        CLI::detail::format_help(out, sub->get_display_name(), wrap(sub->get_description(), kWidth - kNameColumn),
                                 column_width_);
        return out.str();
    }

private:
    static constexpr size_t kWidth = 100, kNameColumn = 34;
};

}  // namespace

std::vector<std::string> normaliseArguments(int argc, char** argv) {
    std::vector<std::string> in(argv + 1, argv + argc), out;
    // pbrt-v4 has no subcommands: a first argument that is not ours starts a render.
    static const char* const kCommands[] = {"render", "mc", "verify", "-h", "--help", "--version"};
    bool named = false;
    if (!in.empty())
        for (const char* c : kCommands) named = named || in[0] == c;
    if (!in.empty() && !named) out.push_back("render");
    for (size_t i = 0; i < in.size(); ++i) {
        const std::string& a = in[i];
        const bool hasNext = i + 1 < in.size();
        if (a == "--stats" && (!hasNext || looksLikeOption(in[i + 1]) || isSceneFile(in[i + 1]))) {
            out.push_back("--stats-print");
        } else if ((a == "--crop" || a == "--cropwindow") && hasNext && in[i + 1].find(',') != std::string::npos) {
            out.push_back(a);
            std::stringstream values(in[++i]);
            for (std::string v; std::getline(values, v, ',');) out.push_back(v);
        } else {
            out.push_back(a);
        }
    }
    return out;
}

std::shared_ptr<CLI::Formatter> wrappingFormatter() { return std::make_shared<WrappingFormatter>(); }

void refuseOptionsAsValues(CLI::App* cmd) {
    for (CLI::Option* opt : cmd->get_options()) {
        if (opt->get_type_size() == 0 || opt->get_positional()) continue;  // flags; the scene file
        opt->check(CLI::Validator(
            [](std::string& text) -> std::string {
                if (!looksLikeOption(text)) return "";
                return "needs a value, not the option \"" + text + "\" (a file whose name starts with '-' is ./" + text +
                       ")";
            },
            ""));
    }
}

}  // namespace ps
