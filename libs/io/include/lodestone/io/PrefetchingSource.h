#pragma once

#include <lodestone/io/DataSource.h>

#include <atomic>
#include <condition_variable>
#include <deque>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

namespace lodestone::io {

/** Reads and decodes ahead on other threads: workers take observations from another source,
 * load their external data and decode their delay-loaded images (CObservation::load(), and
 * the colour PNG / JPEG files, which MRPT decodes only when their pixels are first touched) and
 * queue them, at most `depth` frames ahead of the caller; next() hands them over in the
 * inner source's order. What comes out is exactly what the inner source gives, decoded, so
 * results do not depend on it (and are deterministic: one reader at a time, one order; the
 * decoders only fill in pixels). One difference: an image our PNG reader decoded is held in
 * memory, no longer as a reference to its file (MRPT's CImage takes decoded pixels only so).
 *
 * - `threads` workers share the work: whichever is free reads the next entry (one at a time:
 *   the inner source is sequential) or decodes one already read, so decoding runs on several
 *   cores when one is not enough. A colour PNG of the usual layout (8-bit RGB) is decoded by
 *   our own reader (decodeRgbPng: the same pixels; 6.2 ms a noisy 640x480 frame in a SLAM run
 *   where cv::imread took 12.2), anything else by MRPT.
 * - A fault of the inner source is handed over after every observation before it, as the inner
 *   source itself does. An image that fails to load is left unloaded: the consumer's own load()
 *   meets the same error where it would have without prefetching.
 * - Memory: at most `depth` frames (observations with images or range data) besides the one
 *   the caller holds, and at most kLightPerFrame x `depth` observations in all. The light ones
 *   (magnetometers, odometry) come at several times the camera's rate; counting them against
 *   the depth would leave less than a frame queued, and reading and decoding would wait on the
 *   frame loop instead of running beside it.
 * - The inner source is touched by one worker at a time; `progress` (e.g. a rawlog's fraction
 *   read) is sampled after each read and read back with progress().
 * - `prepare`, if given, is called on each observation once it is decoded, on the worker, before
 *   the caller can have it: what the consumer would compute from the observation alone (an
 *   RGB-D frame's features, lodestone-slam's node decider), done beside the frame loop. It must
 *   be thread-safe and must not throw; its results are its own business (the observation is
 *   handed over as it is). */
class PrefetchingSource : public DataSource {
  public:
    static constexpr std::size_t kLightPerFrame = 64;

    using Prepare = std::function<void(const mrpt::obs::CObservation::Ptr&)>;
    PrefetchingSource(std::unique_ptr<DataSource> inner, std::size_t depth,
                      std::function<double()> progress = {}, std::size_t threads = 1,
                      Prepare prepare = {});
    ~PrefetchingSource() override;
    PrefetchingSource(const PrefetchingSource&) = delete;
    PrefetchingSource& operator=(const PrefetchingSource&) = delete;

    mrpt::obs::CObservation::Ptr next() override;
    std::string name() const override { return name_; }
    double progress() const { return progress_.load(); }

    /** The workers' CPU time so far [s], summed over them: reading entries from the inner
     * source, decoding what they load (external files, images), and `prepare`. */
    struct WorkerTime {
        double readSeconds{0}, decodeSeconds{0}, prepareSeconds{0};
    };
    WorkerTime workerTime() const;

  private:
    struct Slot {
        mrpt::obs::CObservation::Ptr obs;
        bool taken{false};    // a worker is decoding it
        bool decoded{false};  // ready for the caller
        bool heavy{false};    // a frame: counts against the depth
    };
    void run();

    std::unique_ptr<DataSource> inner_;
    const std::string name_;
    const std::size_t depth_;
    std::function<double()> progress_of_;
    Prepare prepare_;
    std::atomic<double> progress_{0};
    mutable std::mutex mutex_;
    std::condition_variable ready_;  // the front slot was decoded, or the end / a fault came
    std::condition_variable work_;   // a slot to decode, room to read, or stop
    std::deque<Slot> queue_;
    std::size_t frames_queued_{0};
    bool reading_{false};  // a worker is inside inner_->next()
    bool done_{false}, stop_{false};
    std::exception_ptr error_;
    WorkerTime time_;                  // guarded by mutex_
    std::vector<std::thread> workers_;  // last: start once everything above exists
};

}  // namespace lodestone::io
