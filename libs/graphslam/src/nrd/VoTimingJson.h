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
            .set("depth_aligned", t.depthAligned)
            .set("depth_joined", t.depthJoined)
            .set("depth_joined_disagreeing", t.depthJoinedDisagreeing);
        JsonObject why;
        for (int f = 0; f < 4; ++f) {
            const auto reason = static_cast<vision::DepthAlignFailure>(f);
            why.set(reason == vision::DepthAlignFailure::None ? "implausible motion" : toString(reason),
                    t.depthFailures[static_cast<std::size_t>(f)]);
        }
        o.set("depth_failed_by_reason", why);
        std::vector<double> observed;
        for (const std::size_t n : t.depthObserved) observed.push_back(static_cast<double>(n));
        o.set("depth_tried_by_directions_pinned", observed);
    }
    return o;
}

}  // namespace lodestone::graphslam::detail
