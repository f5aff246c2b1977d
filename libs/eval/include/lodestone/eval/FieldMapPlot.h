#pragma once

#include <lodestone/io/TumTrajectory.h>
#include <lodestone/plot/PlaneMap.h>

#include <mrpt/poses/CPose3D.h>

#include <optional>
#include <set>
#include <string>
#include <vector>

namespace lodestone::eval {

/** The pose of a timed trajectory at any time between two of its poses (the relative motion
 * between them scaled linearly). No pose before the first, after the last, or between two
 * poses more than `maxGap` seconds apart that are more than `stillRadius` metres apart: the
 * trajectory does not say where the robot was then (a kidnap; a robot that stood still is
 * still known). */
class TrajectoryInterpolator {
  public:
    TrajectoryInterpolator(std::vector<io::TumPose> trajectory, double maxGap,
                           double stillRadius = 0.02);
    std::optional<mrpt::poses::CPose3D> at(double time) const;
    bool empty() const { return poses_.empty(); }
    const std::vector<io::TumPose>& poses() const { return poses_; }
    /** The trajectory from above in pieces, cut where at() does not bridge (kidnaps). */
    std::vector<std::vector<cv::Point2d>> pieces() const;

  private:
    bool bridges(const io::TumPose& a, const io::TumPose& b) const;
    std::vector<io::TumPose> poses_;  // sorted by time
    double max_gap_, still_radius_;
};

/** |B| over the floor: each magnetometer reading placed where its sensor was on the
 * trajectory (robot pose at its time composed with the sensor pose), averaged per cell.
 * Readings come one at a time (a rawlog streamed, or a run's readings kept), memory is the
 * grid's. */
class FieldMapBuilder {
  public:
    /** `maxGap`: see TrajectoryInterpolator; 2 s holds over any pause between nodes of a
     * moving robot, not over a kidnap. */
    FieldMapBuilder(std::vector<io::TumPose> trajectory, double cellSize, double maxGap = 2.0);

    /** Places one reading taken at `time` by a sensor at `sensorOffset` on the robot; false
     * (and counted) when the trajectory has no pose then. */
    bool add(double time, const mrpt::math::TPoint3D& sensorOffset, double magnitude,
             const std::string& label);

    std::size_t placed() const { return placed_; }
    std::size_t unplaced() const { return unplaced_; }
    const plot::ScalarGrid& grid() const { return grid_; }
    const std::set<std::string>& labels() const { return labels_; }

    /** The map with the trajectory over it; title names the sensors and counts. */
    cv::Mat3b render(const std::string& title) const;

  private:
    TrajectoryInterpolator trajectory_;
    plot::ScalarGrid grid_;
    std::size_t placed_{0}, unplaced_{0};
    std::set<std::string> labels_;
};

}  // namespace lodestone::eval
