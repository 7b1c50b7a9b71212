// File-name helpers shared by the parser, the scene builder and the image reader.
#pragma once
#include <algorithm>
#include <cctype>
#include <filesystem>
#include <string>

namespace ps {

// pbrt-v4 resolves every relative path against the directory of the main scene file
// (PBRT-CONVENTIONS §8), not the including file.
inline std::string resolvePath(const std::string& baseDirectory, const std::string& file) {
    std::filesystem::path p(file);
    if (p.is_absolute() || baseDirectory.empty()) return file;
    return (std::filesystem::path(baseDirectory) / p).string();
}

inline std::string toLower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return s;
}

// ".png" for "a/B.PNG".
inline std::string lowerExtension(const std::string& path) {
    return toLower(std::filesystem::path(path).extension().string());
}

}  // namespace ps
