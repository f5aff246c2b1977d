#include <lodestone/config/ProgressBar.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace lodestone::config {

namespace {
std::string clock(double seconds) {
    if (!std::isfinite(seconds) || seconds < 0) return "--:--";
    const long s = std::lround(seconds);
    char buf[32];
    std::snprintf(buf, sizeof buf, "%ld:%02ld", s / 60, s % 60);
    return buf;
}
}  // namespace

ProgressBar::ProgressBar(std::ostream& out, bool terminal, bool quiet)
    : out_(out),
      terminal_(terminal),
      quiet_(quiet),
      start_(std::chrono::steady_clock::now()),
      last_draw_(start_) {}

std::string ProgressBar::line(double fraction, double dataSeconds, double elapsed) const {
    const double speed = elapsed > 0 ? dataSeconds / elapsed : 0;
    const double eta = fraction > 0 ? elapsed * (1 - fraction) / fraction : NAN;
    char buf[160];
    std::snprintf(buf, sizeof buf, "%5.1f %%  %7.1f s of data  %5.2fx real time  elapsed %s  ETA %s",
                  100 * fraction, dataSeconds, speed, clock(elapsed).c_str(), clock(eta).c_str());
    return buf;
}

void ProgressBar::update(double fraction, double dataSeconds) {
    if (quiet_) return;
    fraction = std::clamp(fraction, 0.0, 1.0);
    const auto now = std::chrono::steady_clock::now();
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    if (terminal_) {
        if (drawn_ && now - last_draw_ < std::chrono::milliseconds(200)) return;
        constexpr int kWidth = 30;
        const int filled = static_cast<int>(fraction * kWidth);
        out_ << "\r[" << std::string(filled, '#') << std::string(kWidth - filled, '.') << "] "
             << line(fraction, dataSeconds, elapsed) << std::flush;
        last_draw_ = now;
        drawn_ = true;
        return;
    }
    const int tenth = static_cast<int>(fraction * 10);
    if (tenth > last_tenth_ && tenth < 10) {
        last_tenth_ = tenth;
        out_ << "progress " << line(fraction, dataSeconds, elapsed) << "\n" << std::flush;
    }
}

void ProgressBar::finish(double dataSeconds) {
    if (quiet_) return;
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    if (terminal_ && drawn_) out_ << "\n";
    out_ << "done     " << line(1.0, dataSeconds, elapsed) << "\n" << std::flush;
}

}  // namespace lodestone::config
