#pragma once

#include <lodestone/vision/RgbdFrame.h>
#include <mrpt/config/CLoadableOptions.h>

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <opencv2/features2d.hpp>
#include <vector>

namespace lodestone::config {
class IniSection;
}

namespace lodestone::vision {

/** ORB features of one frame that have a depth, with their 3D points. */
struct FrameFeatures {
    std::vector<cv::KeyPoint> keypoints;
    cv::Mat descriptors;      ///< CV_8UC1, one 32-byte row per keypoint
    Eigen::Matrix3Xf points;  ///< optical frame [m], column i for keypoint i
    std::size_t detected{0};  ///< keypoints found before dropping those without depth
    std::size_t size() const { return keypoints.size(); }
};

/** ORB extraction (OpenCV) followed by back-projection through the depth image. Keypoints
 * whose depth is missing or out of [minDepth, maxDepth] are dropped: they cannot be aligned in
 * 3D. With `depthMask`, ORB searches only the pixels that have such a depth. */
class OrbExtractor {
  public:
    struct Params : public mrpt::config::CLoadableOptions {
        int features{600};        ///< ORB keypoints requested per frame
        double scaleFactor{1.2};  ///< pyramid scale step
        int levels{8};            ///< pyramid levels
        int fastThreshold{20};    ///< FAST corner threshold [grey levels]
        double minDepth{0.3};     ///< [m]
        double maxDepth{6.0};     ///< [m]
        /** Detect only where the depth image has a usable depth: ORB keeps its strongest
         * `features` corners, and a textured far wall beyond the sensor's range can take them
         * all, leaving none that can be aligned in 3D (a corridor's end seen past plain side
         * walls). */
        bool depthMask{false};

        void loadFromConfigFile(const mrpt::config::CConfigFileBase& source,
                                const std::string& section) override;
        /** Reads this part's keys from a section shared with others (which checks strangers). */
        void read(config::IniSection& section);
        void dumpToTextStream(std::ostream& out) const override;
    };

    OrbExtractor();
    explicit OrbExtractor(const Params& params);
    FrameFeatures extract(const RgbdFrame& frame) const;
    const Params& params() const { return params_; }

  private:
    Params params_;
    cv::Ptr<cv::Feature2D> orb_;
};

}  // namespace lodestone::vision
