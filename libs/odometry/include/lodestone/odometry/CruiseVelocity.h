#pragma once

#include <Eigen/Core>

#include <cmath>

namespace lodestone::odometry {

/** The velocity a carrier cruises at, in its own axes, as a function of how fast it turns:
 * its tracked velocity regressed on its turn rate over the last `seconds` of tracking (each
 * step weighed by e^-age/seconds; early on, over what was tracked). It is the mean a velocity
 * nothing measures fades towards (FadingVelocity): a robot driving a corridor keeps its pace
 * through a plain stretch the camera cannot track, where a velocity fading to rest within a
 * second left a 3-5 s stretch 15-55 % short. Steps are counted in tracked time only: a gap
 * measures nothing, so the cruise before it is the cruise after it.
 *
 * Why the turn rate: a robot at a waypoint, a walker at a corner, stop and turn on the spot. A
 * pace carried through such a turn puts the carrier centimetres along its turning heading (a
 * tenth of a metre sideways over a gap at a corner, measured). So the cruise at a turn rate is
 * the window's regression there, and where the carrier turns faster than the window's turn
 * rates reach (their mean plus 2.58 sigma, 99 %: a corner after a straight corridor) nothing
 * is known of its pace, and the cruise is rest. */
class CruiseVelocity {
  public:
    /** `seconds` 0: no cruise (the velocity fades to rest, the cruise stays zero).
     * `rateSigma` [rad/s]: how well a tracked turn rate is known (VO's over a few frames): a
     * spread of turn rates within it says nothing of how the pace follows them. */
    explicit CruiseVelocity(double seconds = 0, double rateSigma = 2 * M_PI / 180)
        : seconds_(seconds), rate_sigma_(rateSigma) {}

    /** A tracked step: the carrier moved `displacement` (in its axes at the step's start) over
     * `seconds`, turning at `turnRate` [rad/s, its magnitude]. Steps of no time, or not
     * finite, are ignored. */
    void add(const Eigen::Vector3d& displacement, double seconds, double turnRate);
    /** The cruise velocity [m/s] in the carrier's axes while it turns at `turnRate` [rad/s,
     * magnitude]: zero before any step, and where it turns faster than the window's rates. */
    Eigen::Vector3d at(double turnRate) const;
    /** Whether anything is known of the pace at `turnRate`: steps were tracked, and it is
     * within the window's turn rates. */
    bool knows(double turnRate) const;
    double seconds() const { return seconds_; }

  private:
    double rateSpread2() const;  ///< the window's turn rates' variance, their own error added

    double seconds_{0}, rate_sigma_{0};
    // (sums over the window, each step weighed by its time and its age: time, time x rate,
    // time x rate^2, displacement, displacement x rate)
    double time_{0}, rate_{0}, rate2_{0};
    Eigen::Vector3d moved_{Eigen::Vector3d::Zero()}, moved_rate_{Eigen::Vector3d::Zero()};
};

}  // namespace lodestone::odometry
