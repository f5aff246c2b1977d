#pragma once

#include <Eigen/Core>

namespace lodestone::odometry {

/** The velocity a carrier cruises at, in its own axes: its tracked velocity averaged over the
 * last `seconds` of tracking (weighed by e^-age/seconds; early on, over what was tracked). It
 * is the mean a
 * velocity nothing measures fades towards (FadingVelocity): a robot driving a corridor keeps
 * its pace through a plain stretch the camera cannot track, where a velocity fading to rest
 * within a second left a 3-5 s stretch 15-55 % short. Its steps are counted in tracked time
 * only: a gap measures nothing, so the cruise before it is the cruise after it. */
class CruiseVelocity {
  public:
    /** `seconds` 0: no cruise (the velocity fades to rest, the mean stays zero). */
    explicit CruiseVelocity(double seconds = 0) : seconds_(seconds) {}

    /** A tracked step: the carrier moved `displacement` (in its axes at the step's start)
     * over `seconds`. Steps of no time, or not finite, are ignored. */
    void add(const Eigen::Vector3d& displacement, double seconds);
    /** The cruise velocity [m/s], in the carrier's axes (zero before any step). */
    const Eigen::Vector3d& mean() const { return mean_; }
    double seconds() const { return seconds_; }

  private:
    double seconds_{0};
    double tracked_{0};  // [s] the steps' time, each weighed as its displacement is
    Eigen::Vector3d moved_{Eigen::Vector3d::Zero()};
    Eigen::Vector3d mean_{Eigen::Vector3d::Zero()};
};

}  // namespace lodestone::odometry
