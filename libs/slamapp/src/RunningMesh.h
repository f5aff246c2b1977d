#pragma once
// --mesh while the run goes: each keyframe's frame fused at its node's pose as the run makes it,
// re-fused when the graph moves it (dense::KeyframeFusion). A live run has no second pass; an
// offline run chooses it by [dense] fusion = while_running. Private to slamapp.

#include <lodestone/dense/KeyframeFusion.h>
#include <lodestone/graphslam/ReportJson.h>
#include <lodestone/graphslam/SlamEngine.h>

#include <mrpt/obs/CObservation3DRangeScan.h>

#include <deque>

#include <map>
#include <memory>
#include <ostream>

namespace lodestone::slamapp::detail {

class RunningMesh {
  public:
    /** Keyframes made after `firstNode` (a loaded map's nodes have no frames here). */
    RunningMesh(const dense::DenseParams& params, const std::string& outDir, graphslam::TNodeID firstNode);

    /** After the engine took `obs`: a keyframe it placed since is fused at its node's pose
     * (from its frame, kept until then), and at most two keyframes the graph moved are re-fused
     * (the farthest first). */
    void observe(const mrpt::obs::CObservation::Ptr& obs, const graphslam::SlamEngine& engine);

    /** After the engine's last optimization: every keyframe moved is re-fused, then meshed;
     * what was fused, for report.json, and why the mesh is empty where it is. */
    graphslam::JsonObject finish(const graphslam::SlamEngine& engine, dense::Mesh& mesh, std::string& why);

  private:
    dense::KeyframeFusion::PoseOf poseOf(const graphslam::SlamEngine& engine) const;

    dense::DenseParams params_;
    dense::KeyframeFusion fusion_;
    graphslam::TNodeID next_;
    std::map<std::uint64_t, Eigen::Isometry3d> opticalOnRobot_;
    std::size_t keyframes_{0};  ///< seen, fused or not (every_keyframe)
    std::size_t unmatched_{0};  ///< keyframes whose frame was no longer kept
    std::deque<std::shared_ptr<const mrpt::obs::CObservation3DRangeScan>> recent_;
};

}  // namespace lodestone::slamapp::detail
