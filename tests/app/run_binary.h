// Runs the pathspace binary with arguments and collects its exit status and output; or starts
// it in the background, to signal it while it renders.
#pragma once
#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>
#include <vector>

namespace ps::test {

// CPU seconds of rendering before a signal, scaled for the sanitizer build (3-5x slower), so
// that its images are as precise as the Release build's.
// (GCC defines __SANITIZE_ADDRESS__; clang 14 only answers __has_feature.)
#if defined(__SANITIZE_ADDRESS__)
#define PS_TEST_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define PS_TEST_ASAN 1
#endif
#endif
inline double cpuSeconds(double release) {
#ifdef PS_TEST_ASAN
    return 4 * release;
#else
    return release;
#endif
}

struct Result {
    int status = -1;
    std::string out;  // stdout and stderr together
};

// A shell command line, its output (stderr included) captured, waited for.
inline Result runCommand(const std::string& commandLine) {
    const std::string cmd = commandLine + " 2>&1";
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

inline Result runPathspace(const std::string& args) { return runCommand(std::string(PATHSPACE_BINARY) + " " + args); }

// A hexadecimal signal mask from /proc/PID/status (bit k-1 = signal k); 0 if unreadable.
inline unsigned long long procStatusMask(pid_t pid, const char* field) {
    std::ifstream f("/proc/" + std::to_string(pid) + "/status");
    std::string line;
    while (std::getline(f, line))
        if (line.rfind(field, 0) == 0) return std::stoull(line.substr(std::strlen(field)), nullptr, 16);
    return 0;
}

// User + system CPU seconds of the whole process, from /proc/PID/stat.
inline double procCpuSeconds(pid_t pid) {
    std::ifstream f("/proc/" + std::to_string(pid) + "/stat");
    std::string text((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    size_t close = text.rfind(')');
    if (close == std::string::npos) return 0;
    std::istringstream in(text.substr(close + 2));
    std::string field;
    unsigned long long utime = 0, stime = 0;
    for (int i = 3; i <= 15 && in >> field; ++i) {  // fields 14 and 15 (1-based, man 5 proc)
        if (i == 14) utime = std::stoull(field);
        if (i == 15) stime = std::stoull(field);
    }
    return double(utime + stime) / double(sysconf(_SC_CLK_TCK));
}

// `pathspace ARGS` in the background. Readiness is read from /proc rather than guessed with
// a sleep, so the signal tests hold on a loaded machine and under the sanitizers: the process
// renders once its signal handlers are installed, and its CPU time says how much it has
// rendered since, whatever the load.
class RunningPathspace {
public:
    explicit RunningPathspace(const std::vector<std::string>& args) {
        std::vector<char*> argv{const_cast<char*>(PATHSPACE_BINARY)};
        for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
        argv.push_back(nullptr);
        pid_ = fork();
        if (pid_ == 0) {
            execv(PATHSPACE_BINARY, argv.data());
            _exit(127);
        }
    }
    ~RunningPathspace() {
        if (pid_ > 0 && !exited_) {
            kill(pid_, SIGKILL);
            waitpid(pid_, nullptr, 0);
        }
    }
    RunningPathspace(const RunningPathspace&) = delete;
    RunningPathspace& operator=(const RunningPathspace&) = delete;

    // Waits until the process renders (it has installed its SIGINT handler, which it does
    // just before the render starts) and has then used `cpuSeconds` of CPU time (all threads).
    // False if it exited first, or after a minute: a watchdog against a hang, not a measurement.
    bool waitUntilRendering(double cpuSeconds) {
        double start = -1;
        return pollUntil([&] {
            if (start < 0 && (procStatusMask(pid_, "SigCgt:") >> (SIGINT - 1) & 1)) start = procCpuSeconds(pid_);
            return start >= 0 && procCpuSeconds(pid_) - start >= cpuSeconds;
        });
    }
    // Sends `sig` and waits until it is no longer pending, i.e. a thread has taken it (two
    // signals sent before either is taken would merge into one).
    bool signalAndWaitTaken(int sig) {
        if (pid_ <= 0 || exited_ || kill(pid_, sig) != 0) return false;
        return pollUntil([&] {
                   return !((procStatusMask(pid_, "ShdPnd:") | procStatusMask(pid_, "SigPnd:")) >> (sig - 1) & 1);
               }) ||
               exited_;
    }
    // The exit status; -1 if it was killed by a signal, -2 if it could not be started.
    int wait() {
        if (pid_ <= 0) return -2;
        if (!exited_) {
            waitpid(pid_, &status_, 0);
            exited_ = true;
        }
        return WIFEXITED(status_) ? WEXITSTATUS(status_) : -1;
    }

private:
    template <class Done>
    bool pollUntil(Done done) {
        auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
        while (std::chrono::steady_clock::now() < deadline) {
            if (pid_ <= 0 || exited_ || waitpid(pid_, &status_, WNOHANG) == pid_) {
                exited_ = pid_ > 0;
                return false;
            }
            if (done()) return true;
            std::this_thread::sleep_for(std::chrono::milliseconds(2));
        }
        return false;
    }
    pid_t pid_ = -1;
    int status_ = 0;
    bool exited_ = false;
};

// A fresh directory per test, removed afterwards.
// A 32x24 diffuse sphere under a white sky, 4 independent samples per pixel: the command
// line's tests render it in a blink.
inline constexpr const char* kSmallScene = R"(LookAt 0 0 5  0 0 0  0 1 0
Camera "perspective" "float fov" [ 30 ]
Film "rgb" "integer xresolution" [ 32 ] "integer yresolution" [ 24 ] "string filename" [ "small.exr" ]
Sampler "independent" "integer pixelsamples" [ 4 ]
WorldBegin
LightSource "infinite" "rgb L" [ 1 1 1 ]
Material "diffuse"
Shape "sphere" "float radius" [ 1 ]
)";

class CliDirTest : public ::testing::Test {
protected:
    void SetUp() override {
        dir = std::filesystem::temp_directory_path() /
              ("pathspace-cli-" + std::to_string(getpid()) + "-" +
               ::testing::UnitTest::GetInstance()->current_test_info()->name());
        std::filesystem::create_directories(dir);
    }
    void TearDown() override { std::filesystem::remove_all(dir); }
    std::string write(const std::string& name, const std::string& text) {
        std::filesystem::path p = dir / name;
        std::ofstream(p) << text;
        return p.string();
    }
    std::filesystem::path dir;
};

}  // namespace ps::test
