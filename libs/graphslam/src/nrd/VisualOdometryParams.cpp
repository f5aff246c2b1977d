// VisualOdometryNRD's keys: [VisualOdometryNRD] and [visual_odometry] read strictly (a bad value
// or an unknown key fails naming it), and the same keys into report.json's params.
#include <lodestone/config/IniSection.h>
#include <lodestone/graphslam/nrd/VisualOdometryNRD.h>

#include <cmath>

namespace lodestone::graphslam {

namespace {
/** The edges VO makes, the relocalization after a loss, the short gap's bridge, the camera. */
void readTracking(config::IniSection& s, VisualOdometryNRD::Params& p) {
    p.lostEdgeSigma = s.getDouble("lost_edge_sigma", p.lostEdgeSigma);
    p.edgeCrossCovariance = s.getBool("edge_cross_covariance", p.edgeCrossCovariance);
    p.relocalizeKeyframes = s.getInt("relocalize_keyframes", p.relocalizeKeyframes);
    if (p.relocalizeKeyframes < 0) s.fail("relocalize_keyframes", "must be >= 0");
    p.bridgeMaxSeconds = s.getDouble("bridge_max_seconds", p.bridgeMaxSeconds);
    p.bridgeAccelSigma = s.getDouble("bridge_accel_sigma", p.bridgeAccelSigma);
    p.bridgeAngularAccelSigma =
        s.getDouble("bridge_angular_accel_sigma", p.bridgeAngularAccelSigma);
    if (!(p.bridgeMaxSeconds >= 0)) s.fail("bridge_max_seconds", "must be >= 0");
    if (!(p.bridgeAccelSigma > 0) || !(p.bridgeAngularAccelSigma > 0))
        s.fail("bridge_accel_sigma", "acceleration sigmas must be > 0");
    p.cameraLabel = s.getString("camera_label", p.cameraLabel);
}

/** The gyro and the bridge it makes across a gap: the fading velocity, the cruise, the depth's correction. */
void readGyroBridge(config::IniSection& s, VisualOdometryNRD::Params& p) {
    p.useGyro = s.getBool("use_gyro", p.useGyro);
    p.gyroLabel = s.getString("gyro_label", p.gyroLabel);
    p.gyro.noiseStd = s.getDouble("gyro_noise_deg", p.gyro.noiseStd * 180 / M_PI) * M_PI / 180;
    p.gyro.biasStd = s.getDouble("gyro_bias_deg", p.gyro.biasStd * 180 / M_PI) * M_PI / 180;
    if (!(p.gyro.noiseStd >= 0)) s.fail("gyro_noise_deg", "must be >= 0");
    if (!(p.gyro.biasStd >= 0)) s.fail("gyro_bias_deg", "must be >= 0");
    p.gyroBridgeMaxSeconds = s.getDouble("gyro_bridge_max_seconds", p.gyroBridgeMaxSeconds);
    auto& fading = p.bridgeVelocity;
    fading.speedSigma = s.getDouble("bridge_speed_sigma", fading.speedSigma);
    fading.correlationSeconds = s.getDouble("bridge_velocity_seconds", fading.correlationSeconds);
    if (!(p.gyroBridgeMaxSeconds >= 0)) s.fail("gyro_bridge_max_seconds", "must be >= 0");
    if (!(fading.speedSigma > 0)) s.fail("bridge_speed_sigma", "must be > 0");
    if (!(fading.correlationSeconds > 0)) s.fail("bridge_velocity_seconds", "must be > 0");
    p.bridgeCruiseSeconds = s.getDouble("bridge_cruise_seconds", p.bridgeCruiseSeconds);
    if (!(p.bridgeCruiseSeconds >= 0)) s.fail("bridge_cruise_seconds", "must be >= 0");
    p.bridgeByDepth = s.getBool("bridge_by_depth", p.bridgeByDepth);
    p.bridgeHeightSigma = s.getDouble("bridge_height_sigma", p.bridgeHeightSigma);
    if (!(p.bridgeHeightSigma >= 0)) s.fail("bridge_height_sigma", "must be >= 0");
}

/** What holds VO's edge from node to node: the height, the motion model. */
void readStepPriors(config::IniSection& s, VisualOdometryNRD::Params& p) {
    p.stepHeightSigma = s.getDouble("step_height_sigma", p.stepHeightSigma);
    if (!(p.stepHeightSigma >= 0)) s.fail("step_height_sigma", "must be >= 0");
    p.stepMotionPrior = s.getBool("step_motion_prior", p.stepMotionPrior);
}

/** The turn measured by the gap's own depth where no gyro is. */
void readDepthTurn(config::IniSection& s, VisualOdometryNRD::Params& p) {
    p.bridgeTurnByDepth = s.getBool("bridge_turn_by_depth", p.bridgeTurnByDepth);
    auto& turn = p.bridgeTurn;
    turn.rate.speedSigma =
        s.getDouble("bridge_turn_rate_sigma_deg", turn.rate.speedSigma * 180 / M_PI) * M_PI / 180;
    turn.rate.correlationSeconds = p.bridgeVelocity.correlationSeconds;
    turn.tiltSigma = s.getDouble("bridge_tilt_sigma_deg", turn.tiltSigma * 180 / M_PI) * M_PI / 180;
    p.bridgeTurnMaxSigma =
        s.getDouble("bridge_turn_max_sigma_deg", p.bridgeTurnMaxSigma * 180 / M_PI) * M_PI / 180;
    if (!(turn.rate.speedSigma > 0)) s.fail("bridge_turn_rate_sigma_deg", "must be > 0");
    if (!(turn.tiltSigma >= 0)) s.fail("bridge_tilt_sigma_deg", "must be >= 0");
    if (!(p.bridgeTurnMaxSigma > 0)) s.fail("bridge_turn_max_sigma_deg", "must be > 0");
    if (p.bridgeByDepth && !p.useGyro && !p.bridgeTurnByDepth)
        s.fail("bridge_by_depth",
               "needs use_gyro = true or bridge_turn_by_depth = true (the depth corrects the "
               "gyro's bridge, or measures the turn too)");
    if (p.bridgeTurnByDepth && !p.bridgeByDepth)
        s.fail("bridge_turn_by_depth", "needs bridge_by_depth = true (the same frames' depth)");
}

/** The accelerometer's up at each node. */
void readGravity(config::IniSection& s, VisualOdometryNRD::Params& p) {
    p.useGravity = s.getBool("use_gravity", p.useGravity);
    auto& g = p.gravity;
    g.biasStd = s.getDouble("accel_bias", g.biasStd);
    g.windowSeconds = s.getDouble("gravity_window_seconds", g.windowSeconds);
    g.motionSeconds = s.getDouble("gravity_motion_seconds", g.motionSeconds);
    if (!(g.biasStd > 0)) s.fail("accel_bias", "must be > 0");
    if (!(g.windowSeconds > 0)) s.fail("gravity_window_seconds", "must be > 0");
    if (!(g.motionSeconds > 0)) s.fail("gravity_motion_seconds", "must be > 0");
    p.bridgeTurn.tiltSeconds = g.motionSeconds;  // (the same carrier's motion: a gait's half period)
    p.bridgeVelocity.acrossSeconds = g.motionSeconds;  // (its sway and bob turn back as often)
    p.gravityVelocitySigma = s.getDouble("gravity_velocity_sigma", p.gravityVelocitySigma);
    if (!(p.gravityVelocitySigma > 0)) s.fail("gravity_velocity_sigma", "must be > 0");
}

/** The carrier's up and height, the floor's; what goes with what. */
void readLevel(config::IniSection& s, VisualOdometryNRD::Params& p) {
    p.carrierTiltSigma =
        s.getDouble("carrier_tilt_sigma_deg", p.carrierTiltSigma * 180 / M_PI) * M_PI / 180;
    if (!(p.carrierTiltSigma >= 0)) s.fail("carrier_tilt_sigma_deg", "must be >= 0");
    p.carrierHeightSigma = s.getDouble("carrier_height_sigma", p.carrierHeightSigma);
    if (!(p.carrierHeightSigma >= 0)) s.fail("carrier_height_sigma", "must be >= 0");
    if (p.carrierHeightSigma > 0 && !(p.useGravity || p.carrierTiltSigma > 0))
        s.fail("carrier_height_sigma",
               "needs use_gravity = true or carrier_tilt_sigma_deg > 0 (a height is along an up: "
               "with none, the nodes' own plane could stand on its edge)");
    p.floorLevel = s.getBool("floor_level", p.floorLevel);
    auto& fit = p.floor.fit;
    fit.minUpSigma = s.getDouble("floor_min_sigma_deg", fit.minUpSigma * 180 / M_PI) * M_PI / 180;
    fit.minHeightSigma = s.getDouble("floor_min_height_sigma", fit.minHeightSigma);
    if (!(fit.minUpSigma > 0)) s.fail("floor_min_sigma_deg", "must be > 0");
    if (!(fit.minHeightSigma > 0)) s.fail("floor_min_height_sigma", "must be > 0");
    if (p.floorLevel && p.carrierHeightSigma > 0)
        s.fail("floor_level",
               "not with carrier_height_sigma > 0 (one level per graph: the floor's or the "
               "carrier's common height)");
    if (p.useGravity && !p.useGyro)
        s.fail("use_gravity",
               "needs use_gyro = true (the gyro turns the window's samples into one frame)");
    if (!(p.lostEdgeSigma > 0)) s.fail("lost_edge_sigma", "must be > 0");
}
}  // namespace

void VisualOdometryNRD::Params::loadFrom(const mrpt::config::CConfigFileBase& ini) {
    Params& p = *this;
    p.visual.loadFromConfigFile(ini, "visual_odometry");
    config::IniSection s(ini, "VisualOdometryNRD", config::sourceName(ini));
    p.read(s);  // NodeSpacing: node and keyframe intervals, map clouds
    readTracking(s, p);
    readGyroBridge(s, p);
    readStepPriors(s, p);
    readDepthTurn(s, p);
    readGravity(s, p);
    readLevel(s, p);
    s.finish();
}

void VisualOdometryNRD::Params::describeAll(JsonObject& params) const {
    NodeSpacing::describe(params);
    params.set("lost_edge_sigma", lostEdgeSigma)
        .set("relocalize_keyframes", relocalizeKeyframes)
        .set("edge_cross_covariance", edgeCrossCovariance)
        .set("bridge_max_seconds", bridgeMaxSeconds)
        .set("step_height_sigma", stepHeightSigma)
        .set("step_motion_prior", stepMotionPrior)
        .set("camera_label", cameraLabel);
    if (useGyro) {
        params.set("gyro_label", gyroLabel)
            .set("gyro_bridge_max_seconds", gyroBridgeMaxSeconds)
            .set("bridge_by_depth", bridgeByDepth)
            .set("bridge_height_sigma", bridgeHeightSigma)
            .set("bridge_speed_sigma", bridgeVelocity.speedSigma)
            .set("bridge_velocity_seconds", bridgeVelocity.correlationSeconds)
            .set("bridge_across_seconds", bridgeVelocity.acrossSeconds)
            .set("bridge_cruise_seconds", bridgeCruiseSeconds)
            .set("use_gravity", useGravity);
    }
    if (bridgeTurnByDepth) {
        if (!useGyro) {
            params.set("gyro_bridge_max_seconds", gyroBridgeMaxSeconds)
                .set("bridge_by_depth", bridgeByDepth)
                .set("bridge_height_sigma", bridgeHeightSigma)
                .set("bridge_speed_sigma", bridgeVelocity.speedSigma)
                .set("bridge_velocity_seconds", bridgeVelocity.correlationSeconds)
                .set("bridge_across_seconds", bridgeVelocity.acrossSeconds)
                .set("bridge_cruise_seconds", bridgeCruiseSeconds);
        }
        params.set("bridge_turn_by_depth", true)
            .set("bridge_turn_rate_sigma_deg", bridgeTurn.rate.speedSigma * 180 / M_PI)
            .set("bridge_tilt_sigma_deg", bridgeTurn.tiltSigma * 180 / M_PI)
            .set("bridge_turn_max_sigma_deg", bridgeTurnMaxSigma * 180 / M_PI);
    }
    if (carrierTiltSigma > 0)
        params.set("carrier_tilt_sigma_deg", carrierTiltSigma * 180 / M_PI);
    if (carrierHeightSigma > 0) params.set("carrier_height_sigma", carrierHeightSigma);
    if (floorLevel) {
        params.set("floor_level", true)
            .set("floor_min_sigma_deg", floor.fit.minUpSigma * 180 / M_PI)
            .set("floor_min_height_sigma", floor.fit.minHeightSigma);
    }
    if (useGravity) {
        params.set("accel_bias", gravity.biasStd)
            .set("gravity_window_seconds", gravity.windowSeconds)
            .set("gravity_motion_seconds", gravity.motionSeconds)
            .set("gravity_velocity_sigma", gravityVelocitySigma);
    }
}

}  // namespace lodestone::graphslam
