#pragma once

#include <lodestone/odometry/FadingVelocity.h>

#include <Eigen/Core>

namespace lodestone::odometry {

/** The carrier's turn across a gap in visual odometry where no gyro measured it: the turn rate
 * a first-order Gauss-Markov process (FadingVelocity's model, on the angular velocity), the
 * rotation it integrates corrected by rotations that the gap frames' depth measured against an
 * earlier frame, in the directions the depth pinned them (DepthBridge's alignments: a wall
 * ahead pins the turn about the vertical and the pitch, a floor or a second wall the rest).
 * A carrier keeps itself upright: with `tiltSigma` its tilt from the start's up is held to
 * about that much, one independent sample of it every `tiltSeconds` - the roll about a
 * plain wall's normal, which the wall does not see, stays bounded instead of wandering off
 * with the turn rate's guess (and with it the next alignments' start).
 *
 * An error-state Kalman filter on the rotation since the start (a right perturbation), the
 * turn rate (in the robot frame) and the rotation at the earlier frame, cloned when it becomes
 * the frame measured from. */
class DepthTurn {
  public:
    struct Params {
        /** [rad/s] per axis, how fast the carrier turns when it does, and [s] how long a turn
         * rate persists. */
        FadingVelocity rate{0.5, 1.0};
        double gateChi2{16.27};  ///< a measured rotation against the prediction (3 dof, 99.9 %)
        /** [rad] how far the carrier's tilt wanders over a gap (a hand holds a camera level to
         * a few degrees, a robot stands on its floor); 0: no such prior. */
        double tiltSigma{0};
        /** [s] the tilt counted as one independent sample per this long (a gait's or a hand's
         * half period). */
        double tiltSeconds{0.25};
    };

    DepthTurn() = default;
    explicit DepthTurn(const Params& params) : params_(params) {}

    /** A gap starts at t0: the turn rate there (robot frame) with its covariance, and the up in
     * the robot frame (for the tilt's prior). */
    void start(double t0, const Eigen::Vector3d& w0, const Eigen::Matrix3d& w0Covariance,
               const Eigen::Vector3d& up = Eigen::Vector3d::UnitZ());
    void predict(double t);
    /** The frame rotations are measured from is now the current one. */
    void anchor();
    /** A rotation measured from that frame to now (R_anchor^T R, robot frame) and its
     * covariance as a right perturbation; false, and nothing changed, where the prediction
     * rules it out (a wrong ICP minimum). */
    bool update(const Eigen::Matrix3d& measured, const Eigen::Matrix3d& covariance);

    /** The rotation since the start and its covariance (right perturbation), and the
     * anchor's rotation. */
    const Eigen::Matrix3d& rotation() const { return R_; }
    Eigen::Matrix3d covariance() const { return P_.topLeftCorner<3, 3>(); }
    const Eigen::Matrix3d& anchorRotation() const { return Rm_; }
    /** The turn rate now (robot frame, rad/s) and its covariance. */
    const Eigen::Vector3d& rate() const { return w_; }
    Eigen::Matrix3d rateCovariance() const { return P_.block<3, 3>(3, 3); }

  private:
    using Matrix9d = Eigen::Matrix<double, 9, 9>;
    /** The tilt's prior over a step of dt (nothing without one). */
    void holdTilt(double dt);

    Params params_;
    double t_{0};
    Eigen::Matrix3d R_{Eigen::Matrix3d::Identity()}, Rm_{Eigen::Matrix3d::Identity()};
    Eigen::Vector3d w_{Eigen::Vector3d::Zero()};
    Eigen::Vector3d up_{Eigen::Vector3d::UnitZ()};
    Matrix9d P_{Matrix9d::Zero()};  // (rotation, turn rate, the anchor's rotation)
};

}  // namespace lodestone::odometry
