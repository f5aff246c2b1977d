#pragma once

#include <lodestone/view/SceneContent.h>

namespace lodestone::graphslam {
class SlamEngine;
}

namespace lodestone::view {

/** The scene of a run as it goes, copied from the engine on its own thread (so the view's
 * thread never touches the engine): nodes coloured by the map group they belong to now - a
 * kidnapped segment its own colour until a relocation joins it to the map, the map's after -
 * the optimizer's closures (kept, and refused in red), odometry edges, each node's mean |B|,
 * the current pose and the keyframes' clouds on their poses now (every n-th point: at most
 * `maxPoints`; 0: none). */
SceneContent snapshotOf(const graphslam::SlamEngine& engine, std::size_t maxPoints = 100000);

}  // namespace lodestone::view
