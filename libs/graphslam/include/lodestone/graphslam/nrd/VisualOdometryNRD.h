#pragma once

#include <lodestone/graphslam/NodeDecider.h>
#include <lodestone/graphslam/nrd/LevelFloor.h>
#include <lodestone/graphslam/nrd/NodeSpacing.h>
#include <lodestone/odometry/CruiseVelocity.h>
#include <lodestone/odometry/DepthBridge.h>
#include <lodestone/odometry/FadingVelocity.h>
#include <lodestone/odometry/GravityEstimator.h>
#include <lodestone/odometry/GyroBiasEstimator.h>
#include <lodestone/odometry/GyroIntegrator.h>
#include <lodestone/odometry/PreparedFrames.h>
#include <lodestone/vision/RgbdVisualOdometry.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/poses/CPose3DPDFGaussian.h>

#include <cmath>
#include <deque>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace lodestone::graphslam {

/** Node registration from RGB-D visual odometry alone, in 6-DoF: for a camera carried by
 * hand, or any recording without wheel odometry (TUM RGB-D, 7-Scenes, 3DMatch). A node when
 * the camera has moved `node_distance` or turned `node_angle_deg` since the last one; the edge
 * is VO's motion composed along its reference frames, with its covariance (first order, MRPT's
 * pose composition), in full SE(3) - the graph is then solved with `[CeresGSO] mode = se3`.
 * Nodes every `keyframe_distance` / `keyframe_angle_deg` are keyframes: the frame's ORB
 * features (from VO's own pass) and, for map.ply, a coloured cloud.
 *
 * VO lost with no wheels to bridge the gap: when VO re-initializes after LOST, the frame it
 * restarts from is first aligned (VO's matching and RANSAC) with the last tracked frame and
 * the segment's latest keyframes (`relocalize_keyframes`, newest first): a view that came back
 * after a blank wall or a blur joins the graph there, with an edge from that frame composed
 * with VO's, and no gap is left - if that edge agrees with where the gap's motion model (the
 * gyro's bridge below, else the last velocity's) puts the frame, at chi-square 99.9 %: features
 * along one edge, a door frame or a corner, align at any turn about it. With a gyro
 * (`use_gyro`) that covers the gap, a gap of up to
 * `gyro_bridge_max_seconds` is bridged by it: the gyro's rotation over the gap, and a
 * translation from the carrier's last velocity fading as a velocity does that nothing measures
 * (a first-order Gauss-Markov process: `bridge_speed_sigma`, `bridge_velocity_seconds`; the
 * velocity VO's over its last 0.3 s), its covariance growing with the gap - the segment goes
 * on, its edge loose where nothing saw the motion (with `bridge_by_depth`, the translation
 * measured by the gap frames' depth where it pins it: odometry::DepthBridge). Where no gyro
 * covers the gap (`bridge_turn_by_depth`), the depth measures the turn as well
 * (odometry::DepthTurn: VO's last turn rate fading, corrected by each aligned frame's rotation
 * where the depth pinned it, the carrier's tilt held to `bridge_tilt_sigma_deg`), and the gap is
 * bridged when that turn is known to `bridge_turn_max_sigma_deg` about every axis. The gyro's bias
 * is learnt meanwhile from VO's rotations between reference frames where the features tracked
 * (GyroBiasEstimator) and taken out of its rates. Else a short gap (`bridge_max_seconds`) is bridged by the camera's
 * last velocity, the edge's covariance that of a constant-velocity model with white-noise
 * acceleration over the gap; after a longer one the frame it starts from is the first node of
 * a new segment, tied to the last node by a very weak edge (`lost_edge_sigma`), as after a
 * kidnap; the visual loop closer relocalizes it (SlamEngine, Relocalizer). Its record carries
 * when tracking was lost and found again.
 *
 * INI: [VisualOdometryNRD] and [visual_odometry]. */
class VisualOdometryNRD : public NodeDecider {
  public:
    struct Params : NodeSpacing {
        Params() {
            // A hand moves the view faster than a robot: keyframes closer together.
            keyframeDistance = 0.30;
            keyframeAngle = 15 * M_PI / 180;
        }
        double lostEdgeSigma{100.0};  ///< [m, rad] of the edge across a VO gap
        /** [m] VO's edge from node to node given that the carrier's height changed by about
         * this at most (`step_height_sigma`; 0: no such prior) - VO's steps towards a plain wall
         * can leave the height to a few features, metres loose. */
        double stepHeightSigma{0};
        /** VO's edge from node to node fused with the carrier's motion model over the same
         * time (`step_motion_prior`): `bridgeVelocity` from VO's velocity, trusted only to the
         * model's speed spread, towards the cruise. Where VO measured the translation (features,
         * depth that pins it) nothing changes; where it did not (depth alone at a plain wall: a
         * direction `unobservedSigma`, metres, loose) the edge holds what a carrier can do in
         * that time, not anything - a graph otherwise slides such nodes along that direction
         * at almost no cost. A gap's edge the same in its tracked part (last node to last
         * tracked frame), before the bridge. */
        bool stepMotionPrior{false};
        /** An edge keeps the correlations of its translation with its rotation that VO's
         * covariance holds (false: each block alone, `edge_cross_covariance`). */
        bool edgeCrossCovariance{true};
        /** After a VO loss, the restart frame is aligned with the last tracked frame and this
         * many of the segment's latest keyframes before anything else (0: never). */
        int relocalizeKeyframes{8};
        /** A gap this short [s] is bridged by the camera's last velocity instead (constant
         * velocity, white-noise acceleration of `bridgeAccelSigma` [m/s^2] and
         * `bridgeAngularAccelSigma` [rad/s^2]: position sigma a dt^2 / 2); 0: never. */
        double bridgeMaxSeconds{0.0};  // (rgbd_only.ini: 1 s, README "Camera-only SLAM")
        double bridgeAccelSigma{1.5};
        double bridgeAngularAccelSigma{3.0};
        std::string cameraLabel;      ///< only this RGB-D label ("": the first one seen)
        /** The gyro's rotation since VO's reference frame as a measurement where the features
         * fail (CObservationIMU rates; `gyroLabel` "": the first gyro seen). */
        bool useGyro{false};
        std::string gyroLabel;
        odometry::GyroIntegrator::Params gyro;
        /** A VO gap the gyro covers, this long at most [s], is bridged by it (0: never). Its
         * translation: the velocity before the gap fading as `bridgeVelocity` says
         * (`bridge_velocity_seconds`, `bridge_speed_sigma`). */
        double gyroBridgeMaxSeconds{10.0};
        odometry::FadingVelocity bridgeVelocity;
        /** [s] The velocity a gap's fades towards: the carrier's cruise at the gap's turn rate,
         * VO's velocity in its axes regressed on its turn rate over this long of tracking, rest
         * where it turns faster than it did then (odometry::CruiseVelocity;
         * `bridge_cruise_seconds`; 0: always rest). */
        double bridgeCruiseSeconds{0};
        /** The gyro's bridge corrected by the depth of the gap's frames (odometry::DepthBridge:
         * each frame's depth aligned with an earlier one measures the translation where it
         * pins it - a plain wall's distance - the fading velocity carrying the rest). */
        bool bridgeByDepth{false};
        /** With it, how far the carrier's height wanders over a gap [m] (the up the
         * accelerometer's, where measured; 0: no such prior): `bridge_height_sigma`. */
        double bridgeHeightSigma{0};
        /** With it and no gyro over the gap: the turn measured by the same frames' depth
         * (`bridge_turn_by_depth`; DepthTurn's model in `bridgeTurn`: the turn rate's spread
         * `bridge_turn_rate_sigma_deg` fading with `bridge_velocity_seconds`, the tilt
         * `bridge_tilt_sigma_deg`), taken where every axis of it is known to
         * `bridgeTurnMaxSigma` [rad] (`bridge_turn_max_sigma_deg`). */
        bool bridgeTurnByDepth{false};
        odometry::DepthTurn::Params bridgeTurn;
        double bridgeTurnMaxSigma{10 * M_PI / 180};
        /** With the gyro: the same IMU's accelerometer, averaged over the last second before
         * each node, gives the node's up - a prior on its roll and pitch in the graph
         * (odometry::GravityEstimator; `accel_bias`, `gravity_window_seconds`,
         * `gravity_motion_seconds`). */
        bool useGravity{false};
        odometry::GravityEstimator::Params gravity;
        /** Where no accelerometer measures it, each node's up is taken to be its robot frame's
         * z to within this [rad] per axis (`carrier_tilt_sigma_deg`; 0: no such prior): a
         * carrier that holds its camera level - a robot on its floor, a walker holding it
         * ahead. Without it nothing bounds the tilt VO's steps chain, and a degree of it is
         * centimetres of height per metre walked. Not for a camera that scans (pointed at a
         * table, a shelf): its tilt is no carrier's. Measured with `carrierHeightSigma`: the
         * hand-held loop gains, the robot's camera loses (docs/results/camera-only.md). */
        double carrierTiltSigma{0};
        /** Each node's height along the map's up held to the carrier's common height within
         * this [m] (`carrier_height_sigma`; 0: no such prior): a carrier on one floor - a robot,
         * a walker's hand bobbing a few centimetres. Along the map's up, which the nodes' ups
         * (the accelerometer's, or the carrier's) hold: a node's height counts once one of
         * them has an up. Not for stairs or ramps. */
        double carrierHeightSigma{0};
        /** Each node's up and height measured by the level surfaces its frame's depth holds -
         * the floor, a ceiling (LevelFloor; `floor_level`, `floor_min_sigma_deg`,
         * `floor_min_height_sigma`): where seen, it replaces the carrier's up, and is fused with
         * the accelerometer's. The floor is assumed level, the carrier nothing. Not with
         * `carrierHeightSigma` (one level per graph). */
        bool floorLevel{false};
        LevelFloor::Params floor;
        /** The carrier's velocity change over the window, taken out of the mean, is VO's: its
         * displacement over `gravityVelocitySeconds` at each end of the window, trusted to
         * `gravityVelocitySigma` per axis [m/s] (`gravity_velocity_sigma`). The same is the
         * velocity a gyro's bridge across a gap starts from. */
        double gravityVelocitySeconds{0.3};
        double gravityVelocitySigma{0.03};
        vision::RgbdVisualOdometry::Params visual;  ///< [visual_odometry]

        /** [VisualOdometryNRD] and [visual_odometry] of `ini` over these values, strictly: a
         * bad value, a key unknown or keys that do not go together fail naming the key. */
        void loadFrom(const mrpt::config::CConfigFileBase& ini);
        /** Every key of the section that applies (the gyro's, the depth's where used) into
         * report.json's params. */
        void describeAll(JsonObject& params) const;
    };

    VisualOdometryNRD();
    void configure(const mrpt::config::CConfigFileBase& ini) override;
    const Params& params() const { return params_; }

    bool updateState(mrpt::obs::CActionCollection::Ptr action,
                     mrpt::obs::CSensoryFrame::Ptr observations,
                     mrpt::obs::CObservation::Ptr observation) override;
    bool finish() override;
    std::set<std::string> requiredObservations() const override {
        return {"CObservation3DRangeScan"};
    }
    global_pose_t getCurrentRobotPosEstimation() const override;
    JsonObject describe() const override;
    /** "tracking", "bridging a gap (N frames)" while VO fails, with the segment after a gap
     * no bridge held. */
    std::string trackingState() const override;
    /** The camera's frames prepared ahead: converted, ORB features, depth cloud. */
    std::function<void(const mrpt::obs::CObservation::Ptr&)> preparer(std::size_t inFlight) override;

  protected:
    bool checkRegistrationCondition() override;

    void keepKeyframeDepth(bool keep) override { keep_depth_ = keep; }

  private:
    void consume(const mrpt::obs::CObservation3DRangeScan::Ptr& scan);
    void consumeGyro(const mrpt::obs::CObservationIMU& imu);
    /** The gyro's (and accelerometer's) samples no frame after `t` can need dropped. */
    void dropGyroBefore(double t);
    /** VO (re)started on this frame: the root, or a gap's end - relocalized, bridged (the
     * gyro, the depth's turn, the last velocity) or a new segment. */
    void restartAt(const mrpt::obs::CObservation3DRangeScan& scan, double t,
                   const vision::VoResult& r, const vision::RgbdFrame& frame,
                   const Eigen::Isometry3d& T_robot_optical);
    /** A tracked frame's step onto the chain of recent frames (the velocity a gap starts
     * from, the window before a node). */
    void extendChain(double t, const mrpt::poses::CPose3DPDFGaussian& motion);
    /** The gyro's rotation from VO's reference frame to time t, in the optical frame. */
    std::optional<vision::RotationPrior> gyroSinceReference(double t,
                                                            const Eigen::Isometry3d& T_robot_optical) const;
    /** The last tracked frame relative to the last node, its rise held to `stepHeightSigma`
     * and, with `stepMotionPrior`, held by the motion model over its time (where a gap's
     * bridge starts). */
    mrpt::poses::CPose3DPDFGaussian lastTrackedHeld() const;
    /** A tracked edge from the last node, `seconds` long, fused with the motion model over
     * that time (`stepMotionPrior`). */
    mrpt::poses::CPose3DPDFGaussian motionHeld(const mrpt::poses::CPose3DPDFGaussian& edge,
                                               double seconds) const;
    /** From the last node to a frame `gap` seconds after the last tracked one, by the last
     * velocity. */
    mrpt::poses::CPose3DPDFGaussian bridge(double gap) const;
    /** The same across a gap from the last tracked frame to time t, by the gyro's rotation and
     * the fading velocity (or, with `bridgeByDepth`, the depth bridge followed up to t);
     * nothing when the gyro does not cover the gap. */
    std::optional<mrpt::poses::CPose3DPDFGaussian> bridgeByGyro(double t) const;
    /** Where no gyro covers the gap: the turn and translation the depth bridge followed up to
     * t, if it measured the turn to `bridgeTurnMaxSigma`. */
    std::optional<mrpt::poses::CPose3DPDFGaussian> bridgeByDepthTurn(double t) const;
    /** The depth bridge's turn known to `bridgeTurnMaxSigma` about every axis. */
    bool depthTurnKnown() const;
    /** VO tracked this frame (or restarted on it): a gap after it starts here. */
    void trackedFrame(const vision::RgbdFrame& frame, const Eigen::Isometry3d& T_robot_optical);
    /** A frame VO did not track, or restarted on: into the gap's depth bridge (started at the
     * last tracked frame), where the gyro covers the gap. */
    void followGap(const vision::RgbdFrame& frame, double t, const Eigen::Isometry3d& T_robot_optical);
    /** The carrier's velocity at the last tracked frame, in that frame [m/s]: VO's
     * displacement over the bridge's velocity time constant, trusted to `gravityVelocitySigma`
     * per axis (`sigma`) or to VO's own covariance of its ends, floored there (`covariance`);
     * where VO has not tracked since it restarted, the velocity carried across the gap before
     * the restart (`carried`), else zero and the carrier's speed spread. */
    struct Velocity {
        Eigen::Vector3d mean{Eigen::Vector3d::Zero()};
        double sigma{0};
        Eigen::Matrix3d covariance{Eigen::Matrix3d::Zero()};
        /** The motion model's estimate across a gap, not VO's measurement: not to be weighed
         * against the carrier's spread again. */
        bool carried{false};
    };
    Velocity velocityAtLastTracked() const;
    /** The tracked frame (in chained_) a window of `seconds` back from the last starts at: the
     * newest one that old, else the oldest. */
    std::size_t windowStart(double seconds) const;
    /** The same for the turn rate [rad/s], from VO's rotation over `gravityVelocitySeconds`. */
    Velocity turnRateAtLastTracked() const;
    /** VO restarts at t after a gap whose turn is known (the gyro's, or the depth's): the
     * carrier's velocity and turn rate at t, in its frame, as the gap's motion model ends -
     * the depth bridge's where it followed the gap, else the last tracked frame's faded. A
     * restart VO fails after again (a plain stretch: a restart every lost_after + 1 frames)
     * bridges its next gap from these, not from a standstill. */
    void carryAcrossGap(double t);
    /** VO's rotation from its old reference to a frame that became the new one, against the
     * gyro's over the same time: the gyro's bias learnt. */
    void learnGyroBias(const vision::VoResult& r, double t,
                       const Eigen::Isometry3d& T_robot_optical);
    /** The node's up at t from the accelerometer, the velocity change VO measured over the
     * window taken out; nothing where VO did not track the whole window. */
    std::optional<AttitudePrior> measuredUp(double t) const;
    /** What node `id` (at t, this frame's) is given of its up and height: the accelerometer's
     * up, the floor's (fused), else the carrier's; nothing where none is used. */
    std::optional<AttitudePrior> nodeAttitude(TNodeID id, double t,
                                              const mrpt::obs::CObservation3DRangeScan& scan);
    /** VO's tracked frame nearest to t (within a frame interval or two), in the frame
     * VO's steps are chained in since the segment's last restart: its index in chained_. */
    std::optional<std::size_t> trackedNear(double t) const;
    /** The restart frame aligned with a recent frame of the segment: the edge from the last
     * node to it, if one aligns and agrees with `expected` (the gap's motion model, when one
     * knows the carrier's motion: chi-square 99.9 %, 6 dof). */
    std::optional<mrpt::poses::CPose3DPDFGaussian> relocalize(
        const vision::FrameFeatures& current, const Eigen::Isometry3d& T_robot_camera,
        const mrpt::poses::CPose3DPDFGaussian* expected);
    /** Node `from`'s pose relative to the last node, with covariance (the segment's edges). */
    mrpt::poses::CPose3DPDFGaussian relativeToLastNode(TNodeID from) const;
    /** A node at this frame: `edge` from the last node (or the root when there is none). */
    void registerAt(const mrpt::obs::CObservation3DRangeScan& scan, double t,
                    const std::shared_ptr<const vision::FrameFeatures>& features,
                    const mrpt::poses::CPose3DPDFGaussian& edge, bool restart);

    /** A frame and its pose relative to the last node, with covariance. */
    struct Anchor {
        double t{NAN};
        mrpt::poses::CPose3DPDFGaussian pdf;
    };

    Params params_;
    vision::RgbdVisualOdometry vo_;
    bool keep_depth_{false};  // keyframes' records carry their depth cloud
    /** Frames VO prepares, ahead on a reader's threads or here (vo_'s parameters only). */
    odometry::PreparedFrames prepared_{[this](vision::RgbdFrame f) { return vo_.prepare(std::move(f)); }};
    odometry::GyroIntegrator gyro_;
    odometry::GyroBiasEstimator gyro_bias_;  // learnt where VO tracks on features
    odometry::GravityEstimator gravity_;
    std::size_t attitude_priors_{0};  // nodes given the accelerometer's up
    std::size_t carrier_ups_{0};      // nodes given the carrier's level up instead
    LevelFloor floor_;                // the floor, where nodes' depth sees it
    std::size_t floor_disagreed_{0};  // nodes whose floor and accelerometer disagreed
    std::optional<vision::RgbdFrame> frame_;         // the frame being consumed (images shared) ...
    std::optional<vision::DepthCloud> frame_cloud_;  // ... and its depth cloud, where prepared
    std::size_t gyro_priors_{0};  // frames given the gyro's rotation
    Anchor reference_;    // VO's reference frame
    double node_time_{NAN};  // the last node's frame's time
    double frame_time_{NAN};  // the last frame's of this camera
    Anchor last_tracked_;  // the last frame VO tracked (it may become the reference)
    std::shared_ptr<const vision::FrameFeatures> last_tracked_features_;
    std::optional<vision::RgbdFrame> last_tracked_frame_;  // (its images shared, not copied)
    Eigen::Isometry3d last_tracked_optical_{Eigen::Isometry3d::Identity()};  // its camera on the robot
    odometry::DepthBridge depth_bridge_;  // the gap since the last tracked frame, by its depth
    odometry::CruiseVelocity cruise_;     // the carrier's pace while VO tracked
    std::size_t bridged_by_depth_{0};     // gyro bridges the depth corrected (of those taken)
    std::size_t bridged_by_depth_turn_{0};  // gaps no gyro covered, bridged by the depth's turn
    std::size_t depth_bridge_aligned_{0}, depth_bridge_rejected_{0};  // gap frames, over the run
    std::size_t depth_bridge_cruising_{0}, depth_bridge_beyond_cruise_{0};  // ... their steps
    std::size_t restarts_carrying_velocity_{0};  // VO restarts a gap's velocity was carried to
    std::deque<std::pair<TNodeID, std::shared_ptr<const vision::FrameFeatures>>> recent_keyframes_;
    mrpt::poses::CPose3D since_keyframe_;  // the last node relative to the last keyframe
    int segment_{0};
    std::size_t frames_{0}, failed_frames_{0}, keyframes_{0}, gaps_{0}, bridged_{0}, relocalized_{0};
    std::size_t bridged_by_gyro_{0};
    std::size_t relocalizations_rejected_{0};  // alignments the gap's motion model ruled out
    std::vector<double> unbridged_gap_seconds_;  // the gaps that opened a new segment
    // VO's tracked frames chained (since the last restart), for the window's velocities
    std::deque<std::pair<double, mrpt::poses::CPose3D>> chained_;
    std::deque<Eigen::Matrix3d> chained_covariance_;  // VO's, of each against its reference
    std::deque<Eigen::Matrix3d> chained_rotation_covariance_;  // (the same for its rotation)
    std::optional<Velocity> carried_velocity_, carried_turn_rate_;  // at the last restart
    /** [rad/s] How well VO's turn rate over a window is known: its rotations no better than its
     * steps' (0.1-0.4 deg RMS at 640x480, docs/results/camera-only.md), two over 0.3 s. */
    static constexpr double kTurnRateFloor = 2 * M_PI / 180;
    mrpt::poses::CPose3D last_step_;  // the last motion between tracked frames ...
    double last_step_seconds_{0};      // ... and how long it took
    std::vector<double> gap_seconds_;  // from the last tracked frame to VO's restart
    std::map<std::string, std::size_t> failures_;  // failed frames by VO's reason
};

}  // namespace lodestone::graphslam
