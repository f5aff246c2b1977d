#include <lodestone/grab/LiveSlamFeed.h>
#include <mrpt/obs/CObservation3DRangeScan.h>

#include <algorithm>

namespace lodestone::grab {

LiveSlamFeed::LiveSlamFeed(double maxLag) : max_lag_(maxLag) {}

void LiveSlamFeed::push(mrpt::obs::CObservation::Ptr obs, double newest) {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        newest_ = std::max(newest_, newest);
        if (abandoned_) return;
        queue_.push_back(std::move(obs));
    }
    arrived_.notify_one();
}

void LiveSlamFeed::close() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        closed_ = true;
    }
    arrived_.notify_all();
}

mrpt::obs::CObservation::Ptr LiveSlamFeed::next() {
    std::unique_lock<std::mutex> lock(mutex_);
    while (true) {
        arrived_.wait(lock, [&] { return !queue_.empty() || closed_; });
        if (queue_.empty()) return nullptr;  // closed and drained
        auto obs = std::move(queue_.front());
        queue_.pop_front();
        const double lag = newest_ - mrpt::Clock::toDouble(obs->timestamp);
        lag_now_ = lag;
        const bool frame = IS_CLASS(*obs, mrpt::obs::CObservation3DRangeScan);
        frames_ += frame;
        if (frame && lag > max_lag_ && !closed_) {
            ++skipped_;  // behind: this frame would only make it later
            continue;
        }
        lags_.push_back(static_cast<float>(lag));
        return obs;
    }
}

void LiveSlamFeed::abandon() {
    std::lock_guard<std::mutex> lock(mutex_);
    abandoned_ = true;
    queue_.clear();
}

LiveSlamFeed::Stats LiveSlamFeed::current() const {
    std::lock_guard<std::mutex> lock(mutex_);
    Stats s;
    s.handed = lags_.size();
    s.skippedFrames = skipped_;
    s.frames = frames_;
    s.lagNow = lag_now_;
    return s;
}

LiveSlamFeed::Stats LiveSlamFeed::stats() const {
    std::lock_guard<std::mutex> lock(mutex_);
    Stats s;
    s.handed = lags_.size();
    s.skippedFrames = skipped_;
    s.frames = frames_;
    s.lagNow = lag_now_;
    if (!lags_.empty()) {
        std::vector<float> v = lags_;
        const auto at = [&](double q) {
            const auto k = static_cast<std::size_t>(q * (v.size() - 1));
            std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
            return static_cast<double>(v[k]);
        };
        s.lagP50 = at(0.5);
        s.lagP99 = at(0.99);
        s.lagMax = *std::max_element(v.begin(), v.end());
    }
    return s;
}

}  // namespace lodestone::grab
