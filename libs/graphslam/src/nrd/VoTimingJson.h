#pragma once
// VO's time per frame by step, for the node deciders' report.json stats.

#include <lodestone/graphslam/ReportJson.h>
#include <lodestone/vision/RgbdVisualOdometry.h>

namespace lodestone::graphslam::detail {

inline JsonObject voTimingJson(const vision::VoTotals& t) {
    const double n = t.frames > 0 ? static_cast<double>(t.frames) : 1.0;
    JsonObject o;
    o.set("frames", t.frames)
        .set("orb", t.ms.orb / n)
        .set("matching", t.ms.matching / n)
        .set("ransac", t.ms.ransac / n);
    // Only with depth alignment on (reports without it stay as they were).
    if (t.ms.depth > 0) {
        o.set("depth", t.ms.depth / n)
            .set("depth_tried", t.depthTried)
            .set("depth_aligned", t.depthAligned);
    }
    return o;
}

}  // namespace lodestone::graphslam::detail
