#include <lodestone/io/PrefetchingSource.h>

#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/obs/CObservationImage.h>
#include <mrpt/obs/CObservationStereoImages.h>

#include <algorithm>

namespace lodestone::io {

namespace {
/** Loads what the caller would load: external range data (load()) and the delay-loaded images,
 * which MRPT decodes only when their pixels are first touched. A file that fails to load is
 * left as it is: the caller meets the same error where it would have. */
void decode(mrpt::obs::CObservation& obs) {
    const auto attempt = [](const auto& f) {
        try {
            f();
        } catch (...) {
        }
    };
    attempt([&] { obs.load(); });
    if (auto* scan = dynamic_cast<mrpt::obs::CObservation3DRangeScan*>(&obs)) {
        if (scan->hasIntensityImage) attempt([&] { scan->intensityImage.forceLoad(); });
    } else if (auto* image = dynamic_cast<mrpt::obs::CObservationImage*>(&obs)) {
        attempt([&] { image->image.forceLoad(); });
    } else if (auto* stereo = dynamic_cast<mrpt::obs::CObservationStereoImages*>(&obs)) {
        attempt([&] { stereo->imageLeft.forceLoad(); });
        if (stereo->hasImageRight) attempt([&] { stereo->imageRight.forceLoad(); });
    }
}
}  // namespace

PrefetchingSource::PrefetchingSource(std::unique_ptr<DataSource> inner, std::size_t depth,
                                     std::function<double()> progress)
    : inner_(std::move(inner)),
      name_(inner_->name()),
      depth_(std::max<std::size_t>(depth, 1)),
      progressOf_(std::move(progress)),
      worker_([this] { run(); }) {}

PrefetchingSource::~PrefetchingSource() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        stop_ = true;
    }
    notFull_.notify_all();
    worker_.join();  // (a read in progress finishes first)
}

void PrefetchingSource::run() {
    try {
        for (;;) {
            {
                std::unique_lock<std::mutex> lock(mutex_);
                notFull_.wait(lock, [&] { return stop_ || queue_.size() < depth_; });
                if (stop_) return;
            }
            auto obs = inner_->next();
            if (obs) decode(*obs);
            if (progressOf_) progress_ = progressOf_();
            std::lock_guard<std::mutex> lock(mutex_);
            if (!obs) {
                done_ = true;
                notEmpty_.notify_one();
                return;
            }
            queue_.push_back(std::move(obs));
            notEmpty_.notify_one();
        }
    } catch (...) {
        std::lock_guard<std::mutex> lock(mutex_);
        error_ = std::current_exception();
        done_ = true;
        notEmpty_.notify_one();
    }
}

mrpt::obs::CObservation::Ptr PrefetchingSource::next() {
    std::unique_lock<std::mutex> lock(mutex_);
    notEmpty_.wait(lock, [&] { return !queue_.empty() || done_; });
    if (!queue_.empty()) {
        auto obs = std::move(queue_.front());
        queue_.pop_front();
        notFull_.notify_one();
        return obs;
    }
    if (error_) {
        const auto e = error_;
        error_ = nullptr;  // (thrown once; the source is exhausted after it)
        std::rethrow_exception(e);
    }
    return nullptr;
}

}  // namespace lodestone::io
