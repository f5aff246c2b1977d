// RgbdVisualOdometry's words: its states' and failures' names, and [visual_odometry] read
// strictly (a bad value names its key) and written back.
#include <lodestone/config/IniSection.h>
#include <lodestone/vision/RgbdVisualOdometry.h>

namespace lodestone::vision {

const char* toString(VoState s) {
    switch (s) {
        case VoState::Initializing:
            return "INITIALIZING";
        case VoState::Tracking:
            return "TRACKING";
        case VoState::Lost:
            return "LOST";
    }
    return "?";
}

const char* toString(VoFailure f) {
    switch (f) {
        case VoFailure::None:
            return "none";
        case VoFailure::NoReference:
            return "no reference frame";
        case VoFailure::FewFeatures:
            return "too few features with depth";
        case VoFailure::FewMatches:
            return "too few matches";
        case VoFailure::NoConsensus:
            return "too few RANSAC inliers";
        case VoFailure::Implausible:
            return "implausible motion";
        case VoFailure::FasterThanCarrier:
            return "faster than the carrier";
    }
    return "?";
}

void RgbdVisualOdometry::Params::loadFromConfigFile(const mrpt::config::CConfigFileBase& source,
                                                    const std::string& section) {
    // One INI section for the whole odometry: each part reads its own keys from it, and then
    // every key of the section must have belonged to someone.
    config::IniSection s(source, section, config::sourceName(source));
    orb.read(s);
    matcher.read(s);
    ransac.read(s);
    lostAfter = s.getInt("lost_after", lostAfter);
    maxTranslation = s.getDouble("max_translation", maxTranslation);
    maxRotation = s.getDouble("max_rotation_deg", maxRotation * 180 / M_PI) * M_PI / 180;
    maxSpeed = s.getDouble("max_speed", maxSpeed);
    stepError = s.getDouble("step_error", stepError);
    maxTurnRate = s.getDouble("max_turn_rate_deg", maxTurnRate * 180 / M_PI) * M_PI / 180;
    stepErrorAngle = s.getDouble("step_error_deg", stepErrorAngle * 180 / M_PI) * M_PI / 180;
    if (!(maxSpeed >= 0)) s.fail("max_speed", "must be >= 0 (0: off)");
    if (!(maxTurnRate >= 0)) s.fail("max_turn_rate_deg", "must be >= 0 (0: off)");
    if (!(stepError >= 0)) s.fail("step_error", "must be >= 0");
    if (!(stepErrorAngle >= 0)) s.fail("step_error_deg", "must be >= 0");
    seed = static_cast<std::uint64_t>(s.getInt("seed", static_cast<int>(seed)));
    keyframeDistance = s.getDouble("keyframe_distance", keyframeDistance);
    keyframeAngle = s.getDouble("keyframe_angle_deg", keyframeAngle * 180 / M_PI) * M_PI / 180;
    const std::string by = s.getString("keyframe_by", "measured");
    if (by == "measured") {
        keyframeBy = KeyframeBy::Measured;
    } else if (by == "predicted") {
        keyframeBy = KeyframeBy::Predicted;
    } else {
        s.fail("keyframe_by", "must be measured or predicted");
    }
    guidedMatching = s.getBool("guided_matching", guidedMatching);
    guidedGateChi2 = s.getDouble("guided_gate_chi2", guidedGateChi2);
    guidedKeypointSigma = s.getDouble("guided_keypoint_sigma", guidedKeypointSigma);
    depthAlignment = s.getBool("depth_alignment", depthAlignment);
    depthWithFeatures = s.getBool("depth_with_features", depthWithFeatures);
    depthStart = s.getBool("depth_start", depthStart);
    depthModelKeyframes = s.getInt("depth_model_keyframes", depthModelKeyframes);
    depthSampling.columns = s.getInt("depth_grid_columns", depthSampling.columns);
    depthSampling.pointsFromCellMean =
        s.getBool("depth_points_from_cell_mean", depthSampling.pointsFromCellMean);
    depthSampling.depthNoise = ransac.depthNoise;
    depthIcp.minObserved = s.getInt("depth_min_observed", depthIcp.minObserved);
    gyroDepthMinObserved = s.getInt("gyro_depth_min_observed", gyroDepthMinObserved);
    const std::string join = s.getString("gyro_with_features", "off");
    if (join == "off") {
        gyroWithFeatures = GyroJoin::Off;
    } else if (join == "tilt") {
        gyroWithFeatures = GyroJoin::Tilt;
    } else if (join == "all") {
        gyroWithFeatures = GyroJoin::All;
    } else {
        s.fail("gyro_with_features", "must be off, tilt or all");
    }
    if (gyroDepthMinObserved < 0 || gyroDepthMinObserved > 6) {
        s.fail("gyro_depth_min_observed", "must be 0..6 (0: off; directions of a rigid motion)");
    }
    if (depthModelKeyframes < 1) s.fail("depth_model_keyframes", "must be >= 1");
    if (depthSampling.columns < 8) s.fail("depth_grid_columns", "must be >= 8");
    if (depthIcp.minObserved < 1 || depthIcp.minObserved > 6) {
        s.fail("depth_min_observed", "must be 1..6 (directions of a rigid motion)");
    }
    if (lostAfter < 1) s.fail("lost_after", "must be >= 1");
    if (!(guidedGateChi2 > 0)) s.fail("guided_gate_chi2", "must be > 0");
    if (!(guidedKeypointSigma > 0)) s.fail("guided_keypoint_sigma", "must be > 0");
    s.finish();
}

void RgbdVisualOdometry::Params::dumpToTextStream(std::ostream& out) const {
    orb.dumpToTextStream(out);
    matcher.dumpToTextStream(out);
    ransac.dumpToTextStream(out);
    out << "lost_after         = " << lostAfter << "  [frames]\n"
        << "max_translation    = " << maxTranslation << "  [m from the reference]\n"
        << "max_rotation_deg   = " << maxRotation * 180 / M_PI << "  [deg from the reference]\n"
        << "max_speed          = " << maxSpeed << "  [m/s since the last tracked frame; 0: off]\n"
        << "step_error         = " << stepError << "  [m]\n"
        << "max_turn_rate_deg  = " << maxTurnRate * 180 / M_PI << "  [deg/s; 0: off]\n"
        << "step_error_deg     = " << stepErrorAngle * 180 / M_PI << "  [deg]\n"
        << "seed               = " << seed << "\n"
        << "keyframe_distance  = " << keyframeDistance << "  [m]\n"
        << "keyframe_angle_deg = " << keyframeAngle * 180 / M_PI << "  [deg]\n"
        << "keyframe_by        = " << (keyframeBy == KeyframeBy::Predicted ? "predicted" : "measured") << "\n"
        << "guided_matching    = " << (guidedMatching ? "true" : "false") << "\n"
        << "guided_gate_chi2   = " << guidedGateChi2 << "  (2 dof)\n"
        << "guided_keypoint_sigma = " << guidedKeypointSigma << "  [px]\n"
        << "depth_alignment    = " << (depthAlignment ? "true" : "false") << "\n"
        << "depth_with_features = " << (depthWithFeatures ? "true" : "false") << "\n"
        << "depth_start        = " << (depthStart ? "true" : "false") << "\n"
        << "depth_model_keyframes = " << depthModelKeyframes << "\n"
        << "depth_grid_columns = " << depthSampling.columns << "\n"
        << "depth_points_from_cell_mean = " << (depthSampling.pointsFromCellMean ? "true" : "false") << "\n"
        << "depth_min_observed = " << depthIcp.minObserved << "  [of 6 directions]\n"
        << "gyro_depth_min_observed = " << gyroDepthMinObserved << "  [of 6; 0: off]\n"
        << "gyro_with_features = "
        << (gyroWithFeatures == GyroJoin::All ? "all" : gyroWithFeatures == GyroJoin::Tilt ? "tilt" : "off")
        << "\n";
}

}  // namespace lodestone::vision
