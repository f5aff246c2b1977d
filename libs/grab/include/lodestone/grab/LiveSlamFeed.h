#pragma once

#include <lodestone/io/DataSource.h>

#include <condition_variable>
#include <deque>
#include <mutex>
#include <vector>

namespace lodestone::grab {

/** The grab's observations, in the order they are written, handed to a SLAM run on another
 * thread. When the run falls behind - the observation it would take next is more than
 * `maxLag` seconds older than the newest one grabbed - RGB-D frames are skipped (never
 * encoder, magnetometer or other samples: they are small and the odometry needs every one)
 * and counted. The lag of every observation handed over is kept for the figures. */
class LiveSlamFeed : public io::DataSource {
  public:
    explicit LiveSlamFeed(double maxLag);

    /** From the grab: an observation just written; `newest` is the newest time grabbed [s]. */
    void push(mrpt::obs::CObservation::Ptr obs, double newest);
    /** No more: next() returns nullptr once the queue is empty. */
    void close();
    /** The reader is gone (its run ended): push() drops from now on, so nothing piles up. */
    void abandon();

    mrpt::obs::CObservation::Ptr next() override;
    std::string name() const override { return "lodestone-grab live stream"; }

    struct Stats {
        std::size_t handed{0}, skippedFrames{0}, frames{0};
        double lagP50{0}, lagP99{0}, lagMax{0};  ///< [s] newest grabbed - observation handed
        double lagNow{0};
    };
    /** Everything, the percentiles sorted from every lag kept: at the end of a run. */
    Stats stats() const;
    /** The current lag and skipped frames only, without the sort: for a status line (the
     * sort would hold the lock the SLAM thread and the writer take). */
    Stats current() const;

  private:
    mutable std::mutex mutex_;
    std::condition_variable arrived_;
    std::deque<mrpt::obs::CObservation::Ptr> queue_;
    double newest_{-1e300};
    bool closed_{false}, abandoned_{false};
    double max_lag_;
    std::vector<float> lags_;
    std::size_t skipped_{0}, frames_{0};
    double lag_now_{0};
};

}  // namespace lodestone::grab
