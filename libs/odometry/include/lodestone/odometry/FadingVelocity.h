#pragma once

#include <Eigen/Core>

namespace lodestone::odometry {

/** Where a carrier went while nothing measured its motion: its velocity a first-order
 * Gauss-Markov process (Ornstein-Uhlenbeck; Singer's manoeuvre model), each axis apart -
 * the velocity known at the start fades with time constant `correlationSeconds` towards zero
 * mean, spread `speedSigma` (how fast the carrier moves when it does). Over a short gap it is a
 * constant-velocity model with white-noise acceleration; over a long one a random walk whose
 * displacement grows with the square root of time, never a straight line at the last speed.
 *
 * With `acrossSeconds`, the axes are the carrier's (x its heading, z up): across its heading
 * (y, z) the velocity fades with that time constant instead. A wheeled robot does not slide
 * sideways; a walker's and a hand's sideways and vertical motion is sway and bob that turns
 * back each half step - carried on at the walk's persistence, the sway measured before or early
 * in a gap became a tenth of a metre per second sideways for seconds.
 *
 * With a `cruise` (CruiseVelocity: the carrier's pace over the last seconds it was tracked),
 * the velocity fades towards it instead of towards rest: v = cruise + an Ornstein-Uhlenbeck
 * deviation, whose spread stays `speedSigma` (so a carrier that stopped in the gap is still
 * inside it). */
struct FadingVelocity {
    double speedSigma{0.5};          ///< [m/s] per axis, the stationary velocity's sigma
    double correlationSeconds{1.0};  ///< [s] how long a velocity persists (along the heading)
    double acrossSeconds{0};         ///< [s] how long across it (y, z); 0: as along

    /** Expected displacement over `seconds` from velocity `v0`: v0 tau (1 - e^-T/tau), tau
     * the axis's (heading x, across y and z, in the axes v0 is given in); with a `cruise` c
     * (same axes), c T + (v0 - c) tau (1 - e^-T/tau). */
    Eigen::Vector3d meanDisplacement(const Eigen::Vector3d& v0, double seconds,
                                     const Eigen::Vector3d& cruise = Eigen::Vector3d::Zero()) const;
    /** Its variance along the heading [m^2]: sigma^2 tau^2 (2 T/tau - 3 + 4 e^-T/tau -
     * e^-2T/tau), and (tau (1 - e^-T/tau))^2 v0Sigma^2 where the start velocity is known to
     * v0Sigma per axis. The largest of the three where `acrossSeconds` is shorter. */
    double displacementVariance(double seconds, double v0Sigma = 0) const;
    /** The same per axis (heading x, across y and z). */
    Eigen::Vector3d displacementVariances(double seconds, double v0Sigma = 0) const;
    /** The velocity `seconds` after it was `v` with covariance `C` (both in the carrier's
     * axes), as the model carries it: each axis faded towards the `cruise` (zero: rest), its
     * spread towards `speedSigma`. Updated in place. */
    void fadeVelocity(double seconds, Eigen::Vector3d& v, Eigen::Matrix3d& C,
                      const Eigen::Vector3d& cruise = Eigen::Vector3d::Zero()) const;
    /** The model across the heading, as a FadingVelocity of its own. */
    FadingVelocity across() const;

    /** The model over one step of `seconds`, per axis, discretized exactly: the displacement
     * and the velocity move as x' = x + carry v, v' = fade v, plus noise of covariance
     * [[qxx, qxv], [qxv, qvv]] (summed over steps: displacementVariance). */
    struct Step {
        double fade{1}, carry{0}, qxx{0}, qxv{0}, qvv{0};
        /** As the transition F and noise Q of a state (displacement, velocity, a clone of the
         * displacement), three axes each - DepthBridge's and DepthTurn's filters. */
        void matrices(Eigen::Matrix<double, 9, 9>& F, Eigen::Matrix<double, 9, 9>& Q) const;
    };
    /** One step along the heading (with no `acrossSeconds`: every axis's). */
    Step step(double seconds) const;
    /** One step of all three axes as F and Q (as Step::matrices) in a frame where the
     * carrier's axes are the columns of `R` (its heading the first): along it `step`'s, across
     * it `across().step`'s. Without `acrossSeconds`, exactly `step(seconds).matrices`. */
    void matrices(double seconds, const Eigen::Matrix3d& R, Eigen::Matrix<double, 9, 9>& F,
                  Eigen::Matrix<double, 9, 9>& Q) const;
    /** What a `cruise` (the carrier's axes) adds to that step's state beside F x: its
     * displacement (T - carry) c and velocity (1 - fade) c, turned by `R` (the clone: nothing). */
    Eigen::Matrix<double, 9, 1> cruiseStep(double seconds, const Eigen::Matrix3d& R,
                                           const Eigen::Vector3d& cruise) const;
};

}  // namespace lodestone::odometry
