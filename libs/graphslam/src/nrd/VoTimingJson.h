#pragma once
// VO's time per frame by step, for the node deciders' report.json stats.

#include <lodestone/graphslam/ReportJson.h>
#include <lodestone/vision/RgbdVisualOdometry.h>

namespace lodestone::graphslam::detail {

inline JsonObject voTimingJson(const vision::VoTotals& t) {
    const double n = t.frames > 0 ? static_cast<double>(t.frames) : 1.0;
    return JsonObject()
        .set("frames", t.frames)
        .set("orb", t.ms.orb / n)
        .set("matching", t.ms.matching / n)
        .set("ransac", t.ms.ransac / n);
}

}  // namespace lodestone::graphslam::detail
