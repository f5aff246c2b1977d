#pragma once

#include <lodestone/dense/TsdfFusion.h>

#include <Eigen/Geometry>
#include <opencv2/core.hpp>

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <fstream>
#include <functional>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

namespace lodestone::dense {

/** The dense model kept up to date while a run goes (BundleFusion's scheme): each keyframe's
 * frame is fused at its node's pose when the keyframe is made; when the graph later moves a
 * node (a loop closure, a relocation's merge) by more than the model can show - a point at the
 * farthest fused depth moving half a voxel - that frame alone is taken out at the pose it was
 * fused at and fused again at the new one. The rest of the model is untouched.
 *
 * Frames are kept for re-fusion in a spill file (the depth as fused and the colour, raw), not in
 * memory. The fusing runs on a worker thread, in the order the run asked for it, so the model
 * is the same whatever the thread's pace. Needs a volume that can take a frame out. */
class KeyframeFusion {
  public:
    using PoseOf = std::function<std::optional<Eigen::Isometry3d>(std::uint64_t id)>;

    /** Throws std::runtime_error naming `spillPath` when it cannot be written, and
     * std::invalid_argument for a volume that cannot take a frame out. */
    KeyframeFusion(const DenseParams& params, const std::string& spillPath);
    ~KeyframeFusion();
    KeyframeFusion(const KeyframeFusion&) = delete;
    KeyframeFusion& operator=(const KeyframeFusion&) = delete;

    /** A new keyframe `id`: its frame kept and fused at `T_world_optical` (the optical frame
     * in the world), or only kept where it has no pose in the model's frame yet (a kidnapped
     * segment before its merge: nullopt), to be fused once it has. Throws
     * std::invalid_argument for images of the wrong type or size, or an `id` added before. */
    void add(std::uint64_t id, const cv::Mat& depth, const cv::Mat& colourBgr,
             const vision::CameraIntrinsics& intrinsics, const std::optional<Eigen::Isometry3d>& T_world_optical);

    /** Asks for the keyframes whose pose (`poseOf`, the optical frame's; nullopt: none in the
     * model's frame) moved beyond the tolerance to be fused again - and those kept without a
     * pose that now have one to be fused - the farthest moved first, at most `budget` of them
     * (0: all). Returns how many were asked for. */
    std::size_t refuseMoved(const PoseOf& poseOf, std::size_t budget = 0);

    /** Waits for the worker, then meshes. */
    Mesh extractMesh();

    struct Stats {
        std::size_t keyframes{0};       ///< kept and fused
        std::size_t withoutDepth{0};    ///< not fused: no usable depth
        std::size_t refusions{0};       ///< frames taken out and fused again
        double fuseSeconds{0};          ///< the worker's time fusing and re-fusing
        double spillSeconds{0};         ///< writing and reading the spill file
        std::size_t spillBytes{0};
        std::size_t volumeBytes{0};
        std::size_t failures{0};  ///< frames the store could not write or read back (left as they were)
        std::string lastFailure;
    };
    /** Waits for the worker. */
    Stats stats();
    /** How far (the tolerance's measure) a point at the farthest fused depth moves between two
     * poses [m]. */
    double displacement(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) const;

  private:
    struct Kept {
        vision::CameraIntrinsics intrinsics;
        bool colour{false};
        std::optional<Eigen::Isometry3d> fusedAt;  ///< where the model holds it (after queued work)
    };
    struct Task {
        std::uint64_t id{0};
        bool store{false};  ///< a new frame: into the store first
        std::optional<Eigen::Isometry3d> takeOutAt, fuseAt;
    };
    void work();
    void run(const Task& task, const Kept& kept, cv::Mat& depth, cv::Mat& colour,
             std::map<std::uint64_t, std::uint64_t>& offsets);
    void store(std::uint64_t id, const cv::Mat& depth, const cv::Mat& colour,
               std::map<std::uint64_t, std::uint64_t>& offsets);
    void readBack(std::uint64_t offset, const Kept& kept, cv::Mat& depth, cv::Mat& colour);
    void wait();

    DenseParams params_;
    TsdfFusion fusion_;
    std::string spillPath_;
    std::fstream spill_;
    std::map<std::uint64_t, Kept> kept_;
    Stats stats_;

    std::mutex mutex_;
    std::condition_variable wake_, idle_;
    std::deque<Task> tasks_;
    std::map<std::uint64_t, std::pair<cv::Mat, cv::Mat>> fresh_;  ///< frames queued for their first fusion
    bool busy_{false}, stop_{false};
    std::thread worker_;
};

}  // namespace lodestone::dense
