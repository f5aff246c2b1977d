#include <lodestone/config/IniSection.h>
#include <lodestone/vision/OrbFeatures.h>

#include <cmath>
#include <opencv2/features2d.hpp>

namespace lodestone::vision {

void OrbExtractor::Params::loadFromConfigFile(const mrpt::config::CConfigFileBase& source,
                                              const std::string& section) {
    config::IniSection s(source, section, config::sourceName(source));
    read(s);
}

void OrbExtractor::Params::read(config::IniSection& s) {
    features = s.getInt("orb_features", features);
    scaleFactor = s.getDouble("orb_scale_factor", scaleFactor);
    levels = s.getInt("orb_levels", levels);
    fastThreshold = s.getInt("orb_fast_threshold", fastThreshold);
    minDepth = s.getDouble("min_depth", minDepth);
    maxDepth = s.getDouble("max_depth", maxDepth);
    depthMask = s.getBool("orb_depth_mask", depthMask);
    if (features < 10) s.fail("orb_features", "must be >= 10");
    if (scaleFactor <= 1.0) s.fail("orb_scale_factor", "must be > 1");
    if (minDepth >= maxDepth) s.fail("max_depth", "must exceed min_depth");
}

void OrbExtractor::Params::dumpToTextStream(std::ostream& out) const {
    out << "orb_features       = " << features << "\n"
        << "orb_scale_factor   = " << scaleFactor << "\n"
        << "orb_levels         = " << levels << "\n"
        << "orb_fast_threshold = " << fastThreshold << "  [grey levels]\n"
        << "min_depth          = " << minDepth << "  [m]\n"
        << "max_depth          = " << maxDepth << "  [m]\n"
        << "orb_depth_mask     = " << (depthMask ? "true" : "false") << "\n";
}

OrbExtractor::OrbExtractor() : OrbExtractor(Params()) {}

OrbExtractor::OrbExtractor(const Params& params)
    : params_(params),
      orb_(cv::ORB::create(params.features, static_cast<float>(params.scaleFactor), params.levels,
                           31, 0, 2, cv::ORB::HARRIS_SCORE, 31, params.fastThreshold)) {}

FrameFeatures OrbExtractor::extract(const RgbdFrame& frame) const {
    FrameFeatures out;
    if (frame.gray.empty()) return out;
    std::vector<cv::KeyPoint> keypoints;
    cv::Mat descriptors;
    cv::Mat mask;
    if (params_.depthMask && frame.depth.size() == frame.gray.size()) {
        // (NaN compares false: no depth, no corner)
        cv::inRange(frame.depth, params_.minDepth, params_.maxDepth, mask);
    }
    orb_->detectAndCompute(frame.gray, mask, keypoints, descriptors);  // (empty mask: none)
    out.detected = keypoints.size();
    if (keypoints.empty() || frame.depth.empty()) return out;

    const auto& K = frame.intrinsics;
    std::vector<int> keep;
    keep.reserve(keypoints.size());
    std::vector<Eigen::Vector3f> points;
    points.reserve(keypoints.size());
    for (std::size_t i = 0; i < keypoints.size(); ++i) {
        const int u = static_cast<int>(std::lround(keypoints[i].pt.x));
        const int v = static_cast<int>(std::lround(keypoints[i].pt.y));
        if (u < 0 || v < 0 || u >= frame.depth.cols || v >= frame.depth.rows) continue;
        const float z = frame.depth.at<float>(v, u);
        if (!std::isfinite(z) || z < params_.minDepth || z > params_.maxDepth) continue;
        keep.push_back(static_cast<int>(i));
        points.emplace_back(static_cast<float>((keypoints[i].pt.x - K.cx) / K.fx * z),
                            static_cast<float>((keypoints[i].pt.y - K.cy) / K.fy * z), z);
    }
    out.keypoints.reserve(keep.size());
    out.descriptors.create(static_cast<int>(keep.size()), descriptors.cols, descriptors.type());
    out.points.resize(3, static_cast<Eigen::Index>(keep.size()));
    for (std::size_t j = 0; j < keep.size(); ++j) {
        out.keypoints.push_back(keypoints[keep[j]]);
        descriptors.row(keep[j]).copyTo(out.descriptors.row(static_cast<int>(j)));
        out.points.col(static_cast<Eigen::Index>(j)) = points[j];
    }
    return out;
}

}  // namespace lodestone::vision
