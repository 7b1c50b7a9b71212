// Replace-by-rename: readers of the target see either the old file or the complete new one,
// and a failed write (full disk, bad directory) leaves the old file as it was. Images and
// render checkpoints are written this way.
#pragma once
#include <initializer_list>
#include <span>
#include <string>

namespace ps {

// Writes `parts` in order to a temporary file beside path, syncs it, renames it over path and
// syncs the directory (so that the rename survives a crash too). On failure the temporary is
// removed, path is untouched, and an InputError says "PATH: cannot write WHAT: " and errno's text.
void writeFileAtomically(const std::string& path, std::initializer_list<std::span<const char>> parts,
                         const std::string& what);

}  // namespace ps
