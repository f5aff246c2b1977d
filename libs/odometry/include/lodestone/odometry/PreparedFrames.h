#pragma once

#include <lodestone/vision/PreparedFrame.h>
#include <mrpt/obs/CObservation3DRangeScan.h>

#include <deque>
#include <functional>
#include <mutex>
#include <string>
#include <utility>

namespace lodestone::odometry {

/** RGB-D frames prepared ahead on other threads - converted (frameFromObservation), their
 * features extracted and depth sampled (vision::RgbdVisualOdometry::prepare) - for the odometry
 * that consumes them, so that its frame loop does not wait on that work.
 *
 * Each is kept against its observation, which it holds (so no other observation can take its
 * address). At most `capacity` wait to be taken; beyond that the oldest is dropped. A frame not
 * prepared ahead, dropped, or whose preparation failed is prepared when taken: the result is
 * the same either way, and a bad frame's error (a range image that is not depth) is thrown by
 * take(), where it would have been without preparing ahead. */
class PreparedFrames {
  public:
    using Prepare = std::function<vision::PreparedFrame(vision::RgbdFrame)>;
    explicit PreparedFrames(Prepare prepare);

    /** How many frames may be prepared and not yet taken (a reader's frames in flight). */
    void setCapacity(std::size_t frames);
    /** Only this camera's frames are prepared ahead from now on (the one the odometry took);
     * empty: every RGB-D observation's. */
    void onlyCamera(const std::string& label);

    /** On any thread: prepares `obs` if it is an RGB-D observation of the camera. */
    void prepareAhead(const mrpt::obs::CObservation::Ptr& obs);
    /** On the consumer's thread: the frame prepared for `obs`, taken out, or prepared now. */
    vision::PreparedFrame take(const mrpt::obs::CObservation3DRangeScan& obs);

    struct Counts {
        std::size_t ahead{0};    ///< frames taken that were prepared ahead
        std::size_t here{0};     ///< frames prepared when taken
        std::size_t dropped{0};  ///< prepared ahead and never taken (capacity, another camera)
    };
    Counts counts() const;

  private:
    Prepare prepare_;
    mutable std::mutex mutex_;
    std::deque<std::pair<mrpt::obs::CObservation::Ptr, vision::PreparedFrame>> ready_;
    std::size_t capacity_{0};
    std::string camera_;
    Counts counts_;
};

}  // namespace lodestone::odometry
