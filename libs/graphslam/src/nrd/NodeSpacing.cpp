#include <lodestone/graphslam/nrd/NodeSpacing.h>

namespace lodestone::graphslam {

void NodeSpacing::read(config::IniSection& s) {
    nodeDistance = s.getDouble("node_distance", nodeDistance);
    nodeAngle = s.getDouble("node_angle_deg", nodeAngle * 180 / M_PI) * M_PI / 180;
    keyframeDistance = s.getDouble("keyframe_distance", keyframeDistance);
    keyframeAngle = s.getDouble("keyframe_angle_deg", keyframeAngle * 180 / M_PI) * M_PI / 180;
    mapPixelStep = s.getInt("map_pixel_step", mapPixelStep);
    mapMaxDepth = s.getDouble("map_max_depth", mapMaxDepth);
    if (!(nodeDistance > 0)) s.fail("node_distance", "must be > 0");
    if (!(nodeAngle > 0)) s.fail("node_angle_deg", "must be > 0");
    if (keyframeDistance < nodeDistance) s.fail("keyframe_distance", "must be >= node_distance");
    if (mapPixelStep < 0) s.fail("map_pixel_step", "must be >= 0");
}

void NodeSpacing::describe(JsonObject& params) const {
    params.set("node_distance", nodeDistance)
        .set("node_angle_deg", nodeAngle * 180 / M_PI)
        .set("keyframe_distance", keyframeDistance)
        .set("keyframe_angle_deg", keyframeAngle * 180 / M_PI)
        .set("map_pixel_step", mapPixelStep);
}

}  // namespace lodestone::graphslam
