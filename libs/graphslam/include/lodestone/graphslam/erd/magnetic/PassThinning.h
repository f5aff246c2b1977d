#pragma once

#include <Eigen/Core>
#include <functional>
#include <vector>

namespace lodestone::graphslam::closure {

/** A stored magnetometer reading where the graph has it. */
struct PlacedReading {
    Eigen::Vector2d at{0, 0};
    double s{0};  ///< [m] travel
    int segment{0};
};

/** Which readings of a map an earlier pass already holds. A map keeps every pass its sessions
 * drove; a loop closer comparing a query with every stored reading would cost more with every
 * session that drove a place again. Reading i is redundant when a kept reading k of another
 * pass (another segment, or at least `minTravelGap` of travel apart) in the same frame lies
 * within `radius` of it and the two passes run together `reach` readings either way (within
 * 2 x `radius` at both ends), the same way or the other: every window through i has a
 * counterpart through k. Readings whose `reach` either way leaves their segment are kept and
 * hold nothing for others. Readings are taken in order: the earliest pass of a line is kept. */
std::vector<char> redundantReadings(const std::vector<PlacedReading>& readings, std::size_t reach,
                                    double radius, double minTravelGap,
                                    const std::function<bool(int, int)>& sameFrame);

}  // namespace lodestone::graphslam::closure
