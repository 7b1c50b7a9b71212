#include "util/input_files.h"

#include <algorithm>
#include <mutex>

namespace ps {

namespace {
std::mutex gMutex;
std::vector<std::string> gFiles;
}  // namespace

void noteInputFile(const std::string& path) {
    std::lock_guard<std::mutex> lock(gMutex);
    if (std::find(gFiles.begin(), gFiles.end(), path) == gFiles.end()) gFiles.push_back(path);
}

std::vector<std::string> inputFiles() {
    std::lock_guard<std::mutex> lock(gMutex);
    return gFiles;
}

}  // namespace ps
