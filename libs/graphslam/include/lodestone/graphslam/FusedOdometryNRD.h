#pragma once

#include <lodestone/graphslam/NodeDecider.h>
#include <lodestone/odometry/FusedOdometry.h>
#include <mrpt/obs/CObservation3DRangeScan.h>

#include <deque>
#include <map>
#include <memory>

namespace lodestone::graphslam {

/** Node registration from the fused wheel + visual odometry (odometry library): a node when
 * the robot has moved `node_distance` or turned `node_angle_deg` since the last one, the edge
 * being the fused motion with its covariance. Nodes are fine-grained (the magnetic matcher's
 * interval); keyframes, a subset spaced by `keyframe_distance` / `keyframe_angle_deg`, carry the
 * RGB-D data (paper 000 §2.3).
 *
 * Kidnapping (CObservationWheelDrop): while the robot is lifted its odometry is ignored; the
 * first node after it is put down starts a new segment, tied to the last node by a very weak
 * edge (`kidnap_edge_sigma`) until a loop closure re-anchors it (SlamEngine).
 *
 * Each node keeps the magnetometer readings since the previous one; each keyframe its ORB
 * features (from the visual odometry's pass) and, for map.ply, a coloured cloud.
 *
 * INI: [FusedOdometryNRD] plus the odometry sections [wheel_odometry], [visual_odometry],
 * [odometry_fusion]. */
class FusedOdometryNRD : public NodeDecider {
  public:
    struct Params {
        double nodeDistance{0.10};            ///< [m]
        double nodeAngle{10 * M_PI / 180};    ///< [rad]
        double keyframeDistance{0.50};        ///< [m]
        double keyframeAngle{20 * M_PI / 180};  ///< [rad]
        int mapPixelStep{8};     ///< keyframe clouds for map.ply: every n-th pixel (0: none)
        double mapMaxDepth{4.0};  ///< [m]
        double kidnapEdgeSigma{100.0};  ///< [m, rad] of the edge across a kidnap
        odometry::FusedOdometry::Params odometry;
    };

    FusedOdometryNRD();
    void configure(const mrpt::config::CConfigFileBase& ini) override;
    /** Replaces the wheel geometry read from the INI (the simulator knows its robot's). */
    void setWheelGeometry(double wheelBase, double wheelRadius, double ticksPerRev);
    const Params& params() const { return params_; }

    bool updateState(mrpt::obs::CActionCollection::Ptr action,
                     mrpt::obs::CSensoryFrame::Ptr observations,
                     mrpt::obs::CObservation::Ptr observation) override;
    bool finish() override;
    std::set<std::string> requiredObservations() const override;
    /** The last node's pose composed with the motion since it. */
    global_pose_t getCurrentRobotPosEstimation() const override;
    JsonObject describe() const override;

  protected:
    bool checkRegistrationCondition() override;

  private:
    void consume(const mrpt::obs::CObservation::Ptr& obs);
    void take(const odometry::FusedOdometry::Estimate& e);
    void onWheelDrop(bool lifted, double t);
    bool registerPending();
    NodeRecord recordFor(double timestamp, bool keyframe);

    Params params_;
    std::unique_ptr<odometry::FusedOdometry> odometry_;
    mrpt::poses::CPosePDFGaussian since_node_;  // fused motion since the last node
    mrpt::poses::CPose2D since_keyframe_;
    double last_time_{0};
    bool have_estimate_{false};
    bool lifted_{false};
    std::optional<double> lift_time_, down_time_;  // [s] of the kidnap being handled
    double restart_lift_{NAN}, restart_down_{NAN};  // of the kidnap the next node ends
    bool segment_closed_{false}, close_segment_{false}, restart_{false};
    int segment_{0};
    std::deque<mrpt::obs::CObservation3DRangeScan::Ptr> recent_frames_;  // not yet resolved
    std::deque<MagneticSample> magnetic_;  // since the last node
    std::map<double, std::shared_ptr<const vision::FrameFeatures>> recent_features_;
    std::size_t frames_{0}, frames_lifted_{0}, kidnaps_{0}, keyframes_{0};
};

}  // namespace lodestone::graphslam
