// Runs the pathspace binary with arguments and collects its exit status and output.
#pragma once
#include <cstdio>
#include <string>
#include <sys/wait.h>

namespace ps::test {

struct Result {
    int status = -1;
    std::string out;  // stdout and stderr together
};

inline Result runPathspace(const std::string& args) {
    std::string cmd = std::string(PATHSPACE_BINARY) + " " + args + " 2>&1";
    Result r;
    FILE* p = popen(cmd.c_str(), "r");
    if (!p) return r;
    char buf[4096];
    size_t n;
    while ((n = fread(buf, 1, sizeof buf, p)) > 0) r.out.append(buf, n);
    int st = pclose(p);
    r.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
    return r;
}

}  // namespace ps::test
