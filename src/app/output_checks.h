// Checks made before a render starts, so that hours of work are not lost to an output that
// cannot be written.
#pragma once
#include <string>

namespace ps {

// Throws InputError unless a file can be created at `path` (its directory is writable and
// it is not a directory): `what` names it in the message ("output", "--json").
void checkFileWritable(const std::string& path, const std::string& what);
// Also requires an image extension writeImage supports.
void checkWritable(const std::string& path);

}  // namespace ps
