#pragma once

#include <mrpt/config/CLoadableOptions.h>

#include <opencv2/core.hpp>
#include <vector>

namespace lodestone::config {
class IniSection;
}

namespace lodestone::vision {

/** Brute-force Hamming matching of binary descriptors with the gates that make its output
 * usable: a mutual best match (cross-check), a maximum distance and, when enabled, Lowe's ratio
 * test against the second best. Descriptors of whole 64-bit words (ORB's 256 bits) are matched
 * by our own kernel (XOR and popcount, one pass for both directions); others by OpenCV's
 * BFMatcher. Both give the same matches. */
class DescriptorMatcher {
  public:
    struct Params : public mrpt::config::CLoadableOptions {
        int maxDistance{64};    ///< Hamming distance above which a pair is no match [bits]
        double ratio{0.0};      ///< best / second-best distance must be below this; 0: off
        bool crossCheck{true};  ///< keep only mutual best matches

        void loadFromConfigFile(const mrpt::config::CConfigFileBase& source,
                                const std::string& section) override;
        /** Reads this part's keys from a section shared with others (which checks strangers). */
        void read(config::IniSection& section);
        void dumpToTextStream(std::ostream& out) const override;
    };

    DescriptorMatcher();
    explicit DescriptorMatcher(const Params& params);

    /** Matches: queryIdx into `query`, trainIdx into `train`. */
    std::vector<cv::DMatch> match(const cv::Mat& query, const cv::Mat& train) const;
    const Params& params() const { return params_; }

  private:
    std::vector<cv::DMatch> matchPacked(const cv::Mat& query, const cv::Mat& train) const;
    std::vector<cv::DMatch> matchWithOpenCv(const cv::Mat& query, const cv::Mat& train) const;
    Params params_;
};

}  // namespace lodestone::vision
