#pragma once

#include <lodestone/graphslam/NodeDecider.h>
#include <lodestone/graphslam/nrd/NodeSpacing.h>
#include <lodestone/graphslam/nrd/KidnapDetector.h>
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
 * Kidnapping: the wheel-drop sensor (CObservationWheelDrop, `kidnap_wheel_drop`) and/or
 * kidnap::KidnapDetector (VO or magnetometers against the encoders, [kidnap_detection]) say
 * when the robot was lifted and put down; while lifted its odometry is ignored; the first node
 * after the put-down starts a new segment, tied to the last node by a very weak edge
 * (`kidnap_edge_sigma`) until a verified relocation joins it to the map (SlamEngine). With the
 * detector on, odometry is held back `latency` seconds so that a lift detected late still ends
 * the odometry edges where it happened.
 *
 * Each node keeps the magnetometer readings since the previous one; each keyframe its ORB
 * features (from the visual odometry's pass) and, for map.ply, a coloured cloud.
 *
 * INI: [FusedOdometryNRD] plus the odometry sections [wheel_odometry], [visual_odometry],
 * [odometry_fusion]. */
class FusedOdometryNRD : public NodeDecider {
  public:
    struct Params : NodeSpacing {
        double kidnapEdgeSigma{100.0};  ///< [m, rad] of the edge across a kidnap
        bool useWheelDrop{true};        ///< take kidnaps from CObservationWheelDrop
        kidnap::KidnapDetector::Params detection;  ///< [kidnap_detection]
        odometry::FusedOdometry::Params odometry;
    };

    FusedOdometryNRD();
    void configure(const mrpt::config::CConfigFileBase& ini) override;
    const Params& params() const { return params_; }

    bool updateState(mrpt::obs::CActionCollection::Ptr action,
                     mrpt::obs::CSensoryFrame::Ptr observations,
                     mrpt::obs::CObservation::Ptr observation) override;
    bool finish() override;
    void continueAfterMap(TNodeID lastMapNode, int segment) override;
    std::set<std::string> requiredObservations() const override;
    /** The last node's pose composed with the motion since it. */
    global_pose_t getCurrentRobotPosEstimation() const override;
    JsonObject describe() const override;
    /** "kidnapped (carried)" between a lift and its put-down, else the visual odometry's. */
    std::string trackingState() const override;
    /** The camera's frames prepared ahead: converted, ORB features, depth cloud. */
    std::function<void(const mrpt::obs::CObservation::Ptr&)> preparer(std::size_t inFlight) override;

  protected:
    bool checkRegistrationCondition() override;

    void keepKeyframeDepth(bool keep) override { keep_depth_ = keep; }

  private:
    void consume(const mrpt::obs::CObservation::Ptr& obs);
    void take(const odometry::FusedOdometry::Estimate& e);
    /** Takes the held-back estimates older than `now` - latency (all for `now` = infinity). */
    void release(double now);
    void onDetectorEvent(const std::optional<kidnap::KidnapDetector::Event>& ev);
    void onWheelDrop(bool lifted, double t);
    bool registerPending();
    NodeRecord recordFor(double timestamp, bool keyframe);

    Params params_;
    std::unique_ptr<odometry::FusedOdometry> odometry_;
    mrpt::poses::CPosePDFGaussian since_node_;  // fused motion since the last node
    // ... and how it moves with the wheels' scales (x, y, phi by left, right)
    Eigen::Matrix<double, 3, 2> since_node_scale_{Eigen::Matrix<double, 3, 2>::Zero()};
    mrpt::poses::CPose2D since_keyframe_;
    double last_time_{0};
    bool have_estimate_{false};
    bool lifted_{false};
    bool keep_depth_{false};  // keyframes' records carry their depth cloud
    std::optional<double> lift_time_, down_time_;  // [s] of the kidnap being handled
    double restart_lift_{NAN}, restart_down_{NAN};  // of the kidnap the next node ends
    bool segment_closed_{false}, close_segment_{false}, restart_{false};
    int segment_{0};
    bool after_map_{false};  // the run continues a loaded map (continueAfterMap)
    std::deque<mrpt::obs::CObservation3DRangeScan::Ptr> recent_frames_;  // not yet resolved
    std::deque<MagneticSample> magnetic_;  // since the last node
    std::map<double, std::shared_ptr<const vision::FrameFeatures>> recent_features_;
    std::unique_ptr<kidnap::KidnapDetector> detector_;  // null when off
    std::deque<odometry::FusedOdometry::Estimate> held_;  // waiting out the detector's latency
    std::string detector_sensor_;  // the magnetometer the detector listens to
    std::size_t frames_{0}, frames_lifted_{0}, kidnaps_{0}, keyframes_{0};
};

}  // namespace lodestone::graphslam
