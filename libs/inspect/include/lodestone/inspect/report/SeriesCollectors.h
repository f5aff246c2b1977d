#pragma once

#include <lodestone/inspect/report/TimeBins.h>
#include <mrpt/obs/CObservation.h>
#include <mrpt/poses/CPose2D.h>

#include <array>
#include <map>
#include <string>
#include <vector>

namespace lodestone::inspect::report {

/** A magnetometer's field components (sensor frame) and |B| over time, as min/max/mean bins. */
struct MagnetometerSeries {
    std::string label;
    std::size_t count{0};
    std::array<TimeBins<EnvelopeBin>, 4> channels;  ///< x, y, z, |B| [uT]
};

/** An odometry source's path from above: the poses it reported (CObservationOdometry) or the
 * increments it integrated (CActionRobotMovement2D), kept where the robot moved 1 cm or turned
 * 2 degrees since the last point kept. */
struct OdometryPath {
    std::string label;
    std::size_t count{0};
    std::vector<mrpt::poses::CPose2D> points;
    double length{0};  ///< [m] travelled along the kept points
};

/** Collects magnetometer series and odometry paths from a rawlog read once; memory grows
 * with the number of sensors and the distance driven (capped), not with the recording's
 * length. */
class SeriesCollectors {
  public:
    /** `time`: seconds since the rawlog's first timestamp. */
    void addObservation(const mrpt::obs::CObservation& obs, double time);
    /** An action collection's robot movements (actions + sensory frames rawlogs). */
    void addActions(const mrpt::serialization::CSerializable& actions);

    std::vector<MagnetometerSeries> magnetometers() const;
    std::vector<OdometryPath> odometry() const;

    static constexpr std::size_t kMaxPathPoints = 50000;  ///< then every other point is dropped

  private:
    void addPose(OdometryPath& path, const mrpt::poses::CPose2D& pose);
    std::map<std::string, MagnetometerSeries> magnetometers_;
    std::map<std::string, OdometryPath> odometry_;
    mrpt::poses::CPose2D actions_pose_;  // the integrated action increments
};

}  // namespace lodestone::inspect::report
