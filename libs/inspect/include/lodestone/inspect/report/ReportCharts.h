#pragma once

#include <lodestone/inspect/report/SensorTimeline.h>
#include <lodestone/inspect/report/SeriesCollectors.h>
#include <lodestone/inspect/report/SlamOutputs.h>

#include <opencv2/core.hpp>

#include <vector>

namespace lodestone::inspect::report {

/** A row per sensor: sample density over time, gaps shaded red, backwards timestamps as
 * orange triangles, wheel drops (lifted red, down green). `span`: [s] of the rawlog. */
cv::Mat3b timelineChart(const std::vector<SensorTimeline>& sensors, double span);

/** One magnetometer: the three components (sensor frame) and |B| over time, each bin's
 * min-max band and mean line. */
cv::Mat3b magnetometerChart(const MagnetometerSeries& series);

/** Every odometry source's path from above (equal aspect), start circled, end crossed. */
cv::Mat3b odometryChart(const std::vector<OdometryPath>& paths);

/** The optimized node trajectory from above, a colour per segment; every proposed loop
 * closure as a line from node to node coloured by the decider that proposed it (kept solid,
 * not kept: thin with a cross at its middle); relocated segments' first nodes as triangles. */
cv::Mat3b graphChart(const SlamOutputs& slam);

/** The engine time spent per node [ms] over the run, keyframes in another colour. */
cv::Mat3b nodeTimeChart(const std::vector<NodeRow>& nodes);

}  // namespace lodestone::inspect::report
