#include "app/output_checks.h"

#include <unistd.h>

#include <cstdio>
#include <filesystem>

#include "image/image.h"
#include "util/error.h"

namespace ps {

void checkFileWritable(const std::string& path, const std::string& what) {
    std::filesystem::path p(path);
    if (std::filesystem::is_directory(p)) throw InputError(what + " \"" + path + "\" is a directory");
    std::filesystem::path dir = p.has_parent_path() ? p.parent_path() : std::filesystem::path(".");
    // Create and remove a probe file: the only test that holds for every filesystem.
    std::filesystem::path probe = dir / (".pathspace-probe-" + std::to_string(getpid()));
    std::FILE* f = std::fopen(probe.c_str(), "wb");
    if (!f) throw InputError(what + " \"" + path + "\": cannot write to directory \"" + dir.string() + "\"");
    std::fclose(f);
    std::filesystem::remove(probe);
}

void checkWritable(const std::string& path) {
    if (!isWritableImageExtension(path))
        throw InputError("output \"" + path + "\": unsupported extension (use .exr, .png or .pfm)");
    checkFileWritable(path, "output");
}

}  // namespace ps
