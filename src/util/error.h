// Errors and warnings shared by every module. Input errors (bad scene, missing file) are
// distinct from internal errors so the command line can exit with distinct codes.
#pragma once
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace ps {

// Where in an input file something is: "file:line:column".
struct SourceLoc {
    std::string file;
    int line = 0, column = 0;
    std::string str() const {
        if (file.empty()) return "<input>";
        if (line <= 0) return file;
        return file + ":" + std::to_string(line) + ":" + std::to_string(column);
    }
};

// A problem with the user's input: message already names the file and place.
class InputError : public std::runtime_error {
public:
    explicit InputError(const std::string& msg) : std::runtime_error(msg) {}
    InputError(const SourceLoc& loc, const std::string& msg)
        : std::runtime_error(loc.str() + ": error: " + msg), loc_(loc) {}
    // The place the message names, for a caller that reports it field by field (the Python
    // module's SceneError); an empty file when the error has no place in an input file.
    const SourceLoc& where() const { return loc_; }

private:
    SourceLoc loc_;
};

// Runs read(), which reads a file that a scene directive names (an image, a PLY mesh): an
// InputError it throws ("mesh.ply: cannot open ...") gains the directive's place and the
// "error:" prefix, like every other input error.
template <typename Read>
auto readNamedBy(const SourceLoc& directive, Read&& read) -> decltype(read()) {
    try {
        return read();
    } catch (const InputError& e) {
        throw InputError(directive, e.what());
    }
}

// Text from an input file, double-quoted for a message: control bytes and bytes outside
// ASCII as \xNN and a backslash as \\ (a binary file must not put raw bytes on the user's
// terminal), cut after maxChars characters with "...".
std::string quoteForMessage(std::string_view text, size_t maxChars = 80);
// A whole message made printable the same way (backslashes kept): what reaches the terminal.
std::string printableMessage(std::string_view text);

// Warnings go to stderr once per distinct message; collected for the statistics.
void warning(const std::string& msg);
void warning(const SourceLoc& loc, const std::string& msg);
int warningCount();
// The distinct warnings so far, in the order they were first given.
std::vector<std::string> warningMessages();
// Silence stderr output of warnings (they are still counted), e.g. in tests.
void setWarningsQuiet(bool quiet);

// While a scene loads, its warnings wait; released, those with a place in an input file come
// out in file order (files in the order first read, then line and column), the others after
// them in the order given. Reading a scene warns as it parses, building it warns later about
// what parsing kept (unused parameters), which would otherwise interleave out of order.
class HeldWarnings {
public:
    HeldWarnings();
    ~HeldWarnings();  // releases them
    HeldWarnings(const HeldWarnings&) = delete;
    HeldWarnings& operator=(const HeldWarnings&) = delete;
};

}  // namespace ps
