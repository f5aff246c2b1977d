#pragma once

#include <lodestone/odometry/CruiseVelocity.h>
#include <lodestone/odometry/DepthTurn.h>
#include <lodestone/odometry/FadingVelocity.h>
#include <lodestone/vision/RgbdFrame.h>
#include <lodestone/vision/depth/DepthCloud.h>
#include <lodestone/vision/depth/DepthModel.h>
#include <lodestone/vision/depth/PointToPlaneIcp.h>

#include <Eigen/Geometry>

#include <cmath>

namespace lodestone::odometry {

/** Where the carrier went across a gap in visual odometry: the fading-velocity motion model
 * (FadingVelocity) corrected by the depth of the gap's frames. Each frame's depth is aligned
 * (point-to-plane ICP, from the gyro's turn and the predicted translation) with an earlier frame
 * of the gap - the last tracked frame first, a new one once the carrier moved `anchorDistance`
 * or turned `anchorAngle` from it - which measures the translation between them in the
 * directions the depth pins (walking at a plain wall: the distance to it) and nothing in the
 * others, where the motion model carries on. No alignment counts as surer than one depth
 * point at the view's median range (the sensor's depth steps are shared by all its points).
 *
 * A Kalman filter on the robot's position and velocity in the robot frame of the last tracked
 * frame, the position at that earlier frame cloned beside them (each alignment measures the
 * difference of the two). Its prediction is FadingVelocity's Ornstein-Uhlenbeck velocity
 * discretized exactly, so with no frame aligned the result is FadingVelocity's mean and
 * variance; an alignment whose translation the prediction rules out (`gateChi2`: a wrong ICP
 * minimum) is left out.
 *
 * Where no gyro measured the turn (`startTurn`, then `add` without a rotation), the depth
 * measures it too: each alignment's rotation corrects a DepthTurn, which predicts the next
 * frame's, and the translation is measured with the turn so corrected. */
class DepthBridge {
  public:
    struct Params {
        FadingVelocity motion;
        vision::DepthSampling sampling;
        vision::PointToPlaneIcp::Params icp;
        double gateChi2{16.27};  ///< an alignment's translation against the prediction (3 dof, 99.9 %)
        /** Frames are aligned with the same earlier frame until the motion since it exceeds
         * this [m] or this turn [rad] (or it no longer aligns). */
        double anchorDistance{0.10};
        double anchorAngle{5 * M_PI / 180};
        /** How far the carrier's height wanders over a gap [m] (a robot on one floor, a hand
         * bobbing and swaying: centimetres, not the metres a drifting vertical velocity gives
         * over seconds); 0: no such prior. The result is conditioned on it. */
        double heightSigma{0};
        DepthTurn::Params turn;  ///< the turn's model, where no gyro measures it
    };

    DepthBridge() : DepthBridge(Params{}) {}
    explicit DepthBridge(const Params& params);

    /** A gap starts after the last tracked frame: its time, depth and optical frame on the
     * robot, and the robot's velocity there (in its frame) with its covariance; `cruise` the
     * velocity it fades towards at the turn rate of each step (CruiseVelocity; none: rest). */
    void start(double t0, const vision::RgbdFrame& lastTracked,
               const Eigen::Isometry3d& T_robot_optical, const Eigen::Vector3d& v0,
               const Eigen::Matrix3d& v0Covariance,
               const Eigen::Vector3d& up = Eigen::Vector3d::UnitZ(),
               const CruiseVelocity& cruise = CruiseVelocity());
    /** No gyro: the turn is the depth's too (DepthTurn), from the turn rate at the start
     * (robot frame, rad/s) and its covariance. After `start`, before the first `add`. */
    void startTurn(const Eigen::Vector3d& w0, const Eigen::Matrix3d& w0Covariance);
    /** A frame in the gap at `t`: `R_0` the robot's rotation since the gap's start (the gyro's,
     * in the start's robot frame). */
    void add(double t, const vision::RgbdFrame& frame, const Eigen::Isometry3d& T_robot_optical,
             const Eigen::Matrix3d& R_0);
    /** The same where the turn is the depth's (after `startTurn`). */
    void add(double t, const vision::RgbdFrame& frame, const Eigen::Isometry3d& T_robot_optical);
    void reset() { active_ = false; }

    bool active() const { return active_; }
    double startTime() const { return t0_; }
    /** The robot's displacement since the start (in the start's robot frame) and its
     * covariance, at the last frame added (at the start: zero); with `heightSigma`, given that
     * the height along `up` changed by about that much at most. */
    Eigen::Vector3d displacement() const;
    Eigen::Matrix3d covariance() const;
    /** The robot's velocity at the last frame added (in the start's robot frame) and its
     * covariance, conditioned as `displacement` is: what a gap that goes on after it carries. */
    Eigen::Vector3d velocity() const;
    Eigen::Matrix3d velocityCovariance() const;
    /** Where the turn is the depth's: the robot's rotation since the start and its covariance
     * (right perturbation; DepthTurn). */
    bool turning() const { return turning_; }
    Eigen::Matrix3d rotation() const { return turn_.rotation(); }
    Eigen::Matrix3d rotationCovariance() const { return turn_.covariance(); }
    /** The turn rate there (robot frame, rad/s) and its covariance. */
    const Eigen::Vector3d& turnRate() const { return turn_.rate(); }
    Eigen::Matrix3d turnRateCovariance() const { return turn_.rateCovariance(); }
    /** Frames of this gap whose depth measured the motion, and those left out by the gate. */
    int aligned() const { return aligned_; }
    int rejected() const { return rejected_; }
    /** With a cruise: steps of this gap that went on at it, and those turning faster than it
     * knows (faded to rest). */
    int cruising() const { return cruising_; }
    int beyondCruise() const { return beyond_cruise_; }

  private:
    using Vector9d = Eigen::Matrix<double, 9, 1>;
    using Matrix9d = Eigen::Matrix<double, 9, 9>;
    void addFrame(double t, const vision::RgbdFrame& frame,
                  const Eigen::Isometry3d& T_robot_optical, const Eigen::Matrix3d* gyro);
    /** The motion model to `t`, the carrier turned by `R_0` since the start. */
    void predict(double t, const Eigen::Matrix3d& R_0);
    /** The frame's depth aligned with the model frame's, from the predicted motion (`R_0` the
     * rotation since the start); nothing where it did not align. */
    bool align(const vision::DepthCloud& cloud, const Eigen::Isometry3d& T_robot_optical,
               const Eigen::Matrix3d& R_0, vision::DepthAlignment& d) const;
    /** The alignment's rotation of the robot from the model frame into the DepthTurn. */
    bool measureTurn(const vision::DepthAlignment& d, const vision::DepthCloud& cloud,
                     const Eigen::Isometry3d& T_robot_optical);
    /** Its translation from the model frame to this one, in the model frame's robot axes, and
     * its covariance. */
    void measure(const vision::DepthAlignment& d, const vision::DepthCloud& cloud,
                 const Eigen::Isometry3d& T_robot_optical, const Eigen::Matrix3d& R_0,
                 Eigen::Vector3d& z, Eigen::Matrix3d& Z) const;
    /** The model frame becomes this one: its cloud, and the position cloned. */
    void anchor(vision::DepthCloud cloud, const Eigen::Isometry3d& T_robot_optical,
                const Eigen::Matrix3d& R_0);

    Params params_;
    bool active_{false};
    double t0_{0}, t_{0};
    Vector9d x_{Vector9d::Zero()};  // position, velocity, the position at the model frame
    Matrix9d P_{Matrix9d::Zero()};
    vision::DepthModel model_{1};
    Eigen::Matrix3d R_0m_{Eigen::Matrix3d::Identity()};  // the model frame's rotation
    Eigen::Isometry3d T_robot_optical_m_{Eigen::Isometry3d::Identity()};
    Eigen::Vector3d up_{Eigen::Vector3d::UnitZ()};
    CruiseVelocity cruise_;
    Eigen::Matrix3d R_predicted_{Eigen::Matrix3d::Identity()};  // the turn at the last prediction
    int aligned_{0}, rejected_{0}, cruising_{0}, beyond_cruise_{0};
    bool turning_{false};
    DepthTurn turn_;
};

}  // namespace lodestone::odometry
