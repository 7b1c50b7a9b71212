// Every file a scene reads (scene files, included ones, meshes, images, lens and spectrum
// files), noted by the readers themselves, so that a checkpoint can tell whether any of them
// has changed since (transport/checkpoint.h).
#pragma once
#include <string>
#include <vector>

namespace ps {

// Notes that `path` is read (thread-safe; a file read twice is listed once).
void noteInputFile(const std::string& path);
// The files noted so far by this process, in the order first read.
std::vector<std::string> inputFiles();

}  // namespace ps
