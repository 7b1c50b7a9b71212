#include "transport/render_monitor.h"

#include <algorithm>
#include <cstdio>
#include <string>
#include <unistd.h>

namespace ps {

namespace {

std::string formatSeconds(double s) {
    char buf[32];
    if (s < 60) std::snprintf(buf, sizeof buf, "%.1fs", s);
    else if (s < 3600) std::snprintf(buf, sizeof buf, "%dm%02ds", int(s) / 60, int(s) % 60);
    else std::snprintf(buf, sizeof buf, "%dh%02dm", int(s) / 3600, (int(s) % 3600) / 60);
    return buf;
}

}  // namespace

Monitor::Monitor(bool show, double timeLimit, const std::atomic<bool>* cancel, std::atomic<bool>& stop,
                 const std::atomic<long long>& done, long long total, const char* phase,
                 const ProgressCallback* callback)
    : show_(show), timeLimit_(timeLimit), cancel_(cancel), stop_(stop), done_(done), total_(total), phase_(phase),
      callback_(callback && *callback ? callback : nullptr),
      start_(std::chrono::steady_clock::now()), interactive_(isatty(fileno(stderr)) != 0), thread_([this] { run(); }) {}

Monitor::~Monitor() {
    {
        std::lock_guard<std::mutex> lock(m_);
        finished_ = true;
    }
    cv_.notify_all();
    thread_.join();
    if (show_) {
        print(true);
        std::fputc('\n', stderr);
    }
    if (callback_) (*callback_)(figures(true));
}

void Monitor::run() {
    std::unique_lock<std::mutex> lock(m_);
    while (!finished_) {
        cv_.wait_for(lock, std::chrono::milliseconds(100));
        if (finished_) break;
        if ((cancel_ && cancel_->load()) || (timeLimit_ > 0 && elapsed() >= timeLimit_)) stop_ = true;
        // Redraw in place on a terminal; elsewhere (logs, CI) only the final line is printed.
        if (++ticks_ % 3 != 0) continue;
        if (show_ && interactive_) print(false);
        if (callback_) {
            lock.unlock();  // the callback may take its time (the Python module waits for the GIL)
            (*callback_)(figures(false));
            lock.lock();
        }
    }
}

Progress Monitor::figures(bool final) const {
    Progress p{phase_, 0, elapsed(), 0, final};
    p.fraction = total_ > 0 ? std::min(1.0, double(done_.load()) / double(total_)) : 1.0;
    const double t = p.elapsed, frac = p.fraction;
    if (!final) {
        if (timeLimit_ > 0) p.eta = std::max(0.0, std::min(timeLimit_ - t, t / std::max(frac, 1e-9) - t));
        else if (frac > 0) p.eta = t / frac - t;
    }
    return p;
}

void Monitor::print(bool final) {
    const Progress p = figures(final);
    int width = 30, filled = int(p.fraction * width + 0.5);
    std::string bar(filled, '=');
    bar.resize(width, ' ');
    std::fprintf(stderr, "\r%s [%s] %5.1f%%  elapsed %s  eta %s   ", phase_, bar.c_str(), 100 * p.fraction,
                 formatSeconds(p.elapsed).c_str(), formatSeconds(p.eta).c_str());
    std::fflush(stderr);
}

}  // namespace ps
