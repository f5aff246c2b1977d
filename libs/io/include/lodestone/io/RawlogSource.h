#pragma once

#include <lodestone/io/DataSource.h>
#include <lodestone/io/RawlogFormat.h>
#include <lodestone/io/RawlogReader.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/poses/CPose2D.h>

#include <cstdint>
#include <exception>
#include <queue>
#include <vector>

namespace lodestone::io {

/** A DataSource over a rawlog file of either format, plain or gzip, streaming.
 *
 * - Sensory frames are flattened into their observations.
 * - Odometry actions (CActionRobotMovement2D) become CObservationOdometry with the pose and
 *   encoder ticks accumulated from the increments, label `odometryLabel`, so that one code path
 *   serves both formats. Other actions are skipped (counted in skippedActions()). An action
 *   without a timestamp (old MRPT datasets) takes the next observation's; an encoder flag that
 *   is neither 0 nor 1 (an old format version that did not store it) means no ticks
 *   (unknownEncoderFlags()).
 * - Observations are released in timestamp order through a bounded reorder window: MRPT
 *   drivers write each sensor when it is grabbed, so neighbouring entries can be slightly out
 *   of order. An observation older than one already released is still released (counted in
 *   outOfOrder()).
 * - Delay-loaded images are looked up in `imagesDir`, or the `<name>_Images` folder beside
 *   the rawlog when empty (MRPT's convention).
 * On corrupt input every observation read before the fault is released first, then the
 * RawlogReadError is thrown. */
class RawlogSource : public DataSource {
  public:
    struct Options {
        std::string imagesDir;                  ///< external images; empty: auto-detect
        std::size_t reorderWindow{64};          ///< observations held back for sorting
        std::string odometryLabel{"ODOMETRY"};  ///< label for odometry made from actions
    };

    explicit RawlogSource(const std::string& path);
    RawlogSource(const std::string& path, Options options);

    mrpt::obs::CObservation::Ptr next() override;
    std::string name() const override { return reader_.path(); }

    RawlogFormat format() const { return format_; }
    /** How far through the file the reading is, 0..1. */
    double fractionRead() const { return reader_.fractionRead(); }
    std::size_t entriesRead() const { return entries_read_; }
    std::size_t outOfOrder() const { return out_of_order_; }
    std::size_t skippedActions() const { return skipped_actions_; }
    std::size_t unknownEncoderFlags() const { return unknown_encoder_flags_; }
    const std::string& imagesDir() const { return options_.imagesDir; }

  private:
    struct Pending {
        mrpt::Clock::time_point stamp;
        std::uint64_t sequence;
        mrpt::obs::CObservation::Ptr obs;
        bool operator>(const Pending& o) const {
            return stamp != o.stamp ? stamp > o.stamp : sequence > o.sequence;
        }
    };

    bool readOneEntry();  // false at the end of the file or after a fault
    void push(mrpt::obs::CObservation::Ptr obs);
    void pushOdometryFromActions(const mrpt::serialization::CSerializable& actions);
    mrpt::obs::CObservation::Ptr pop();

    RawlogReader reader_;
    Options options_;
    RawlogFormat format_{RawlogFormat::Empty};
    std::priority_queue<Pending, std::vector<Pending>, std::greater<Pending>> window_;
    std::uint64_t sequence_{0};
    bool input_done_{false};
    std::exception_ptr pending_error_;
    mrpt::Clock::time_point last_released_{};
    bool released_any_{false};
    std::size_t entries_read_{0}, out_of_order_{0}, skipped_actions_{0},
        unknown_encoder_flags_{0};
    // Accumulated odometry for actions -> CObservationOdometry.
    mrpt::poses::CPose2D odometry_pose_;
    std::int64_t left_ticks_{0}, right_ticks_{0};
    std::vector<mrpt::obs::CObservationOdometry::Ptr> unstamped_;  // waiting for a timestamp
    mrpt::Clock::time_point latest_stamp_{};
};

}  // namespace lodestone::io
