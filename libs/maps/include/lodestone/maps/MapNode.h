#pragma once

#include <lodestone/graphslam/NodeStore.h>
#include <mrpt/serialization/CSerializable.h>

#include <cstdint>

namespace lodestone::maps {

/** One node of a saved map as MRPT's versioned serialization stores it: what the engine keeps
 * per node beside its pose (graphslam::NodeRecord: time, segment, keyframe features and where
 * the camera sits, the magnetometer readings since the node before) and the session that made
 * it. The pose itself is the graph's. Keyframe clouds are not kept (map.ply is a run's output,
 * not what a later run matches against). */
class CMapNode : public mrpt::serialization::CSerializable {
    DEFINE_SERIALIZABLE(CMapNode, lodestone::maps)

  public:
    std::uint64_t id{0};
    std::uint32_t session{0};  ///< 0: the run that made the map; one more per later session
    graphslam::NodeRecord record;
};

/** A sensor label a map can hold: 1-256 letters, digits and `_-.:/+` (the manifest lists them
 * space-separated in an INI value, where `\`, `;`, `#` and `$` mean something). */
bool isMapLabel(const std::string& label);

}  // namespace lodestone::maps
