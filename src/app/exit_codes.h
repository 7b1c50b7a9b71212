// Exit statuses of the pathspace command (documented in the README and --help).
#pragma once

namespace ps {
constexpr int kExitOk = 0;
constexpr int kExitInternalError = 1;  // a bug or an environment failure (e.g. Embree)
constexpr int kExitBadInput = 2;       // bad command line, scene, mesh, image or output path
constexpr int kExitInterrupted = 130;  // stopped by SIGINT/SIGTERM; the partial image was written
}  // namespace ps
