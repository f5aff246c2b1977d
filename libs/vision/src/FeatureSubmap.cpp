#include <lodestone/vision/FeatureSubmap.h>

#include <nanoflann.hpp>
#include <opencv2/core.hpp>

#include <cmath>
#include <limits>
#include <numeric>

namespace lodestone::vision {

namespace {
/** nanoflann's view of the submap's points. */
struct PointCloud {
    const std::vector<Eigen::Vector3f>& pts;
    std::size_t kdtree_get_point_count() const { return pts.size(); }
    float kdtree_get_pt(std::size_t i, std::size_t d) const { return pts[i][static_cast<int>(d)]; }
    template <class BBox>
    bool kdtree_get_bbox(BBox&) const {
        return false;
    }
};
using PointTree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, PointCloud>,
                                                      PointCloud, 3>;

double yawOf(const Eigen::Isometry3d& T) { return std::atan2(T.linear()(1, 0), T.linear()(0, 0)); }
}  // namespace

FeatureSubmap::FeatureSubmap() : FeatureSubmap(Params{}) {}
FeatureSubmap::FeatureSubmap(Params params) : params_(params) {}

std::size_t FeatureSubmap::add(std::int64_t node, const Eigen::Isometry3d& T_submap_robot,
                               const Eigen::Isometry3d& T_robot_camera,
                               std::shared_ptr<const FrameFeatures> features) {
    members_.push_back({node, T_submap_robot, T_robot_camera, features});
    strongest_.clear();
    if (!features || features->size() == 0) return 0;
    // Eq. (1): the keyframe's points in the submap frame.
    const Eigen::Isometry3f T = (T_submap_robot * T_robot_camera).cast<float>();
    const std::size_t before = points_.size();
    std::size_t merged = 0;
    PointCloud cloud{points_};
    std::unique_ptr<PointTree> tree;
    if (before > 0) {
        tree = std::make_unique<PointTree>(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(10));
        tree->buildIndex();
    }
    const float r2 = static_cast<float>(params_.mergeRadius * params_.mergeRadius);
    std::vector<std::pair<std::uint32_t, float>> near;
    for (std::size_t i = 0; i < features->size(); ++i) {
        const Eigen::Vector3f p = T * features->points.col(static_cast<Eigen::Index>(i));
        const cv::Mat d = features->descriptors.row(static_cast<int>(i));
        std::size_t best = std::numeric_limits<std::size_t>::max();
        int bestDistance = params_.mergeMaxDistance + 1;
        if (tree) {
            near.clear();
            tree->radiusSearch(p.data(), r2, near, nanoflann::SearchParams(32, 0, false));
            for (const auto& [idx, dist2] : near) {
                if (idx >= before) continue;  // only features of earlier keyframes
                const int h = static_cast<int>(cv::norm(d, descriptors_.row(static_cast<int>(idx)),
                                                        cv::NORM_HAMMING));
                if (h < bestDistance) {
                    bestDistance = h;
                    best = idx;
                }
            }
        }
        if (best != std::numeric_limits<std::size_t>::max()) {
            // Seen again: average the position over its sightings.
            const float n = static_cast<float>(sightings_[best]);
            points_[best] = (points_[best] * n + p) / (n + 1);
            ++sightings_[best];
            ++merged;
        } else {
            points_.push_back(p);
            sightings_.push_back(1);
            descriptors_.push_back(d);
        }
    }
    return merged;
}

const std::vector<int>& FeatureSubmap::strongestFirst() const {
    if (strongest_.size() != points_.size()) {
        strongest_.resize(points_.size());
        std::iota(strongest_.begin(), strongest_.end(), 0);
        std::stable_sort(strongest_.begin(), strongest_.end(),
                         [&](int a, int b) { return sightings_[a] > sightings_[b]; });
    }
    return strongest_;
}

Eigen::Vector3d FeatureSubmap::centre() const {
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (const auto& m : members_) c += m.T_submap_robot.translation();
    return members_.empty() ? c : Eigen::Vector3d(c / static_cast<double>(members_.size()));
}

Eigen::Matrix3Xd FeatureSubmap::points() const {
    Eigen::Matrix3Xd m(3, static_cast<Eigen::Index>(points_.size()));
    for (std::size_t i = 0; i < points_.size(); ++i) m.col(static_cast<Eigen::Index>(i)) = points_[i].cast<double>();
    return m;
}

const FeatureSubmap::Member& FeatureSubmap::nearestMember(const Eigen::Isometry3d& pose) const {
    const Member* best = &members_.front();
    double bestCost = std::numeric_limits<double>::max();
    const double yaw = yawOf(pose);
    for (const auto& m : members_) {
        const double dyaw = std::abs(std::remainder(yawOf(m.T_submap_robot) - yaw, 2 * M_PI));
        const double cost = (m.T_submap_robot.translation() - pose.translation()).norm() + 0.5 * dyaw;
        if (cost < bestCost) {
            bestCost = cost;
            best = &m;
        }
    }
    return *best;
}

}  // namespace lodestone::vision
