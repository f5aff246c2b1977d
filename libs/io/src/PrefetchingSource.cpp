#include <lodestone/io/PngFile.h>
#include <lodestone/io/PrefetchingSource.h>

#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/obs/CObservationImage.h>
#include <mrpt/obs/CObservationStereoImages.h>

#include <algorithm>
#include <cctype>
#include <ctime>

namespace lodestone::io {

namespace {
bool endsWithPng(const std::string& path) {
    if (path.size() < 4) return false;
    std::string ext = path.substr(path.size() - 4);
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
    return ext == ".png";
}

/** A delay-loaded image loaded: a colour PNG by the fast decoder (the same pixels), anything
 * else - or a PNG it does not take - by MRPT. */
void loadImage(mrpt::img::CImage& image) {
    if (image.isExternallyStored()) {
        const std::string path = image.getExternalStorageFileAbsolutePath();
        if (endsWithPng(path)) {
            if (auto bgr = decodeRgbPng(path)) {
                image = mrpt::img::CImage(*bgr, mrpt::img::SHALLOW_COPY);
                return;
            }
        }
    }
    image.forceLoad();
}

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
        if (scan->hasIntensityImage) attempt([&] { loadImage(scan->intensityImage); });
    } else if (auto* image = dynamic_cast<mrpt::obs::CObservationImage*>(&obs)) {
        attempt([&] { loadImage(image->image); });
    } else if (auto* stereo = dynamic_cast<mrpt::obs::CObservationStereoImages*>(&obs)) {
        attempt([&] { stereo->imageLeft.forceLoad(); });
        if (stereo->hasImageRight) attempt([&] { stereo->imageRight.forceLoad(); });
    }
}
/** This thread's CPU time [s]: what a worker's work costs, not counting the time it was
 * preempted (on one core the frame loop and the workers take turns). */
double threadCpuSeconds() {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

/** Observations whose decoded data are large (images, range data): the frames. */
bool isFrame(const mrpt::obs::CObservation& obs) {
    return dynamic_cast<const mrpt::obs::CObservation3DRangeScan*>(&obs) ||
           dynamic_cast<const mrpt::obs::CObservationImage*>(&obs) ||
           dynamic_cast<const mrpt::obs::CObservationStereoImages*>(&obs);
}
}  // namespace

PrefetchingSource::PrefetchingSource(std::unique_ptr<DataSource> inner, std::size_t depth,
                                     std::function<double()> progress, std::size_t threads,
                                     Prepare prepare)
    : inner_(std::move(inner)),
      name_(inner_->name()),
      depth_(std::max<std::size_t>(depth, 1)),
      progress_of_(std::move(progress)),
      prepare_(std::move(prepare)) {
    for (std::size_t k = 0; k < std::max<std::size_t>(threads, 1); ++k) {
        workers_.emplace_back([this] { run(); });
    }
}

PrefetchingSource::~PrefetchingSource() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        stop_ = true;
    }
    work_.notify_all();
    for (auto& w : workers_) w.join();  // (reads and decodes in progress finish first)
}

void PrefetchingSource::run() {
    std::unique_lock<std::mutex> lock(mutex_);
    for (;;) {
        // Decoding comes first (the caller waits for the front); else read the next entry.
        const auto undecoded = [&] {
            return std::find_if(queue_.begin(), queue_.end(),
                                [](const Slot& s) { return !s.taken; });
        };
        work_.wait(lock, [&] {
            return stop_ || undecoded() != queue_.end() ||
                   (!reading_ && !done_ && frames_queued_ < depth_ &&
                    queue_.size() < kLightPerFrame * depth_);
        });
        if (stop_) return;
        auto slot = undecoded();
        if (slot != queue_.end()) {
            slot->taken = true;
            const auto obs = slot->obs;  // (the deque may grow meanwhile: hold the pointer)
            lock.unlock();
            const double t0 = threadCpuSeconds();
            decode(*obs);
            const double t1 = threadCpuSeconds();
            if (prepare_) prepare_(obs);
            const double t2 = threadCpuSeconds();
            lock.lock();
            time_.decodeSeconds += t1 - t0;
            time_.prepareSeconds += t2 - t1;
            for (auto& s : queue_) {
                if (s.obs == obs) s.decoded = true;
            }
            ready_.notify_all();
            continue;
        }
        reading_ = true;
        lock.unlock();
        mrpt::obs::CObservation::Ptr obs;
        std::exception_ptr fault;
        const double t0 = threadCpuSeconds();
        try {
            obs = inner_->next();
        } catch (...) {
            fault = std::current_exception();
        }
        const double t1 = threadCpuSeconds();
        if (progress_of_) progress_ = progress_of_();
        lock.lock();
        reading_ = false;
        time_.readSeconds += t1 - t0;
        if (fault || !obs) {
            error_ = fault;
            done_ = true;
            ready_.notify_all();
            work_.notify_all();
            continue;  // (other workers may still be decoding; this one waits for stop)
        }
        const bool heavy = isFrame(*obs);
        frames_queued_ += heavy;
        queue_.push_back({obs, false, false, heavy});
        work_.notify_all();
    }
}

PrefetchingSource::WorkerTime PrefetchingSource::workerTime() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return time_;
}

mrpt::obs::CObservation::Ptr PrefetchingSource::next() {
    std::unique_lock<std::mutex> lock(mutex_);
    ready_.wait(lock, [&] { return (!queue_.empty() && queue_.front().decoded) || (queue_.empty() && done_); });
    if (!queue_.empty()) {
        auto obs = std::move(queue_.front().obs);
        frames_queued_ -= queue_.front().heavy;
        queue_.pop_front();
        work_.notify_all();
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
