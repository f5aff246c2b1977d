#pragma once

#include <lodestone/config/IniSection.h>
#include <lodestone/graphslam/ReportJson.h>

#include <cmath>

namespace lodestone::graphslam {

/** How far apart a node decider places nodes and RGB-D keyframes, and what keyframes keep for
 * map.ply: the keys every node decider's INI section shares. */
struct NodeSpacing {
    double nodeDistance{0.10};              ///< [m]
    double nodeAngle{10 * M_PI / 180};      ///< [rad]
    double keyframeDistance{0.50};          ///< [m]
    double keyframeAngle{20 * M_PI / 180};  ///< [rad]
    int mapPixelStep{8};                    ///< keyframe clouds for map.ply: every n-th pixel (0: none)
    double mapMaxDepth{4.0};                ///< [m]

    /** node_distance, node_angle_deg, keyframe_distance, keyframe_angle_deg, map_pixel_step,
     * map_max_depth from `s` (these defaults where absent); a bad value fails naming the key. */
    void read(config::IniSection& s);
    /** The same keys into report.json's params. */
    void describe(JsonObject& params) const;
};

}  // namespace lodestone::graphslam
