// Runs the pathspace binary as K processes under mpirun on this machine (over loopback), at
// once or in the background to signal it. Tests skip when mpirun is absent or the binary was
// built without MPI (then mpirun would start K independent renders).
#pragma once
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>
#include <vector>

#include "run_binary.h"
#include "sky_scene.h"

namespace ps::test {

// mpirun's path, or "" (with the reason in `why`) when MPI renders cannot be tested here.
inline std::string mpirunPath(std::string& why) {
#if !PATHSPACE_TEST_MPI
    why = "pathspace was built without MPI (PATHSPACE_MPI; scripts/setup.sh installs Open MPI)";
    return "";
#else
    for (const char* dir : {"/usr/bin", "/usr/local/bin", "/bin"}) {
        std::string p = std::string(dir) + "/mpirun";
        if (access(p.c_str(), X_OK) == 0) return p;
    }
    why = "mpirun not found (scripts/setup.sh installs openmpi-bin)";
    return "";
#endif
}

#define PS_SKIP_WITHOUT_MPI()                                        \
    do {                                                             \
        std::string why;                                             \
        if (::ps::test::mpirunPath(why).empty()) GTEST_SKIP() << why; \
    } while (0)

// One machine: more processes than cores (--oversubscribe), root in CI, no core binding (each
// process may run its --threads), and a watchdog: a job that hangs is terminated after 60 s.
inline std::vector<std::string> mpirunArgs(int processes) {
    std::string why;
    return {"/usr/bin/timeout", "60", mpirunPath(why), "--oversubscribe", "--allow-run-as-root", "--bind-to", "none",
            "-n", std::to_string(processes), PATHSPACE_BINARY};
}

// `mpirun -n K pathspace ARGS`, waited for.
inline Result runMpi(int processes, const std::string& args) {
    std::string cmd;
    for (const std::string& a : mpirunArgs(processes)) cmd += a + " ";
    return runCommand(cmd + args);
}

// `mpirun -n K pathspace ARGS` in the background, to signal it or one of its processes.
class RunningMpiJob {
public:
    RunningMpiJob(int processes, const std::vector<std::string>& args) : processes_(processes) {
        std::vector<std::string> all = mpirunArgs(processes);
        all.insert(all.end(), args.begin(), args.end());
        std::vector<char*> argv;
        for (std::string& a : all) argv.push_back(a.data());
        argv.push_back(nullptr);
        pid_ = fork();
        if (pid_ == 0) {
            execv(argv[0], argv.data());
            _exit(127);
        }
    }
    ~RunningMpiJob() {
        if (pid_ > 0 && !exited_) {
            kill(pid_, SIGTERM);  // timeout passes it to mpirun, which ends the job
            waitpid(pid_, nullptr, 0);
        }
    }
    RunningMpiJob(const RunningMpiJob&) = delete;
    RunningMpiJob& operator=(const RunningMpiJob&) = delete;

    // Waits until every process renders (has its SIGINT handler) and has then used
    // `cpuSeconds` of CPU time; false if the job ended first or after a minute.
    bool waitUntilRendering(double cpuSeconds) {
        std::vector<double> start;
        auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
        while (std::chrono::steady_clock::now() < deadline) {
            if (waitpid(pid_, &status_, WNOHANG) == pid_) {
                exited_ = true;
                return false;
            }
            ranks_ = renderers();
            if (int(ranks_.size()) == processes_) {
                start.resize(ranks_.size(), -1);
                bool all = true;
                for (size_t i = 0; i < ranks_.size(); ++i) {
                    if (start[i] < 0 && (procStatusMask(ranks_[i], "SigCgt:") >> (SIGINT - 1) & 1))
                        start[i] = procCpuSeconds(ranks_[i]);
                    all = all && start[i] >= 0 && procCpuSeconds(ranks_[i]) - start[i] >= cpuSeconds;
                }
                if (all) return true;
            }
            std::this_thread::sleep_for(std::chrono::milliseconds(5));
        }
        return false;
    }
    // The pathspace processes (after waitUntilRendering), in no particular order.
    const std::vector<pid_t>& ranks() const { return ranks_; }
    // Signals mpirun itself (as Ctrl-C in its terminal would).
    void signalLauncher(int sig) { kill(mpirunPid(), sig); }
    // The job's exit status (mpirun's), -1 if killed by a signal.
    int wait() {
        if (!exited_) {
            waitpid(pid_, &status_, 0);
            exited_ = true;
        }
        return WIFEXITED(status_) ? WEXITSTATUS(status_) : -1;
    }

private:
    static std::vector<pid_t> children(pid_t pid) {
        std::ifstream f("/proc/" + std::to_string(pid) + "/task/" + std::to_string(pid) + "/children");
        std::vector<pid_t> c;
        for (pid_t p; f >> p;) c.push_back(p);
        return c;
    }
    pid_t mpirunPid() const {
        std::vector<pid_t> c = children(pid_);  // timeout's child
        return c.empty() ? -1 : c[0];
    }
    std::vector<pid_t> renderers() const {
        pid_t m = mpirunPid();
        return m > 0 ? children(m) : std::vector<pid_t>{};
    }

    int processes_;
    pid_t pid_ = -1;
    int status_ = 0;
    bool exited_ = false;
    std::vector<pid_t> ranks_;
};

// A test directory with kSkyScene, and the files a render writes there.
class SkyRenderTest : public CliDirTest {
protected:
    std::string scene() { return write("s.pbrt", kSkyScene); }
    std::string path(const std::string& name) const { return (dir / name).string(); }
    static std::string bytes(const std::string& file) {
        std::ifstream f(file, std::ios::binary);
        return std::string((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    }
    nlohmann::json stats(const std::string& name) const { return nlohmann::json::parse(std::ifstream(path(name))); }
};

}  // namespace ps::test
