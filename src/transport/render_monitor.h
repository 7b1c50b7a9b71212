// Progress on stderr and the stop signal (time budget, cancellation), from its own thread.
#pragma once
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <thread>

namespace ps {

// The progress line's figures, for a caller that shows them its own way (the Python module).
struct Progress {
    const char* phase;  // "rendering", or a Metropolis render's start-up phase
    double fraction;    // done, in [0, 1]
    double elapsed;     // seconds
    double eta;         // seconds left (0 on the final report)
    bool final;         // the last report of this phase
};
using ProgressCallback = std::function<void(const Progress&)>;

class Monitor {
public:
    // Sets `stop` once the time limit (seconds, 0 = none) has passed or *cancel is set;
    // shows done/total as a progress bar when `show`, named `phase` ("rendering", or a
    // Metropolis render's "bootstrap"); hands the same figures to `callback` when it is set
    // (from the monitor's thread, a few times a second, and once more at the end).
    Monitor(bool show, double timeLimit, const std::atomic<bool>* cancel, std::atomic<bool>& stop,
            const std::atomic<long long>& done, long long total, const char* phase = "rendering",
            const ProgressCallback* callback = nullptr);
    ~Monitor();
    double elapsed() const {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    }
    double timeLimit() const { return timeLimit_; }

private:
    void run();
    Progress figures(bool final) const;
    void print(bool final);

    bool show_;
    double timeLimit_;
    const std::atomic<bool>* cancel_;
    std::atomic<bool>& stop_;
    const std::atomic<long long>& done_;
    long long total_;
    const char* phase_;
    const ProgressCallback* callback_;
    std::chrono::steady_clock::time_point start_;
    std::mutex m_;
    std::condition_variable cv_;
    bool finished_ = false;
    int ticks_ = 0;
    bool interactive_;
    std::thread thread_;
};

}  // namespace ps
