#include <lodestone/config/IniSection.h>
#include <lodestone/vision/DescriptorMatcher.h>

#include <climits>
#include <opencv2/features2d.hpp>

#include "HammingKernel.h"

namespace lodestone::vision {

void DescriptorMatcher::Params::loadFromConfigFile(const mrpt::config::CConfigFileBase& source,
                                                   const std::string& section) {
    config::IniSection s(source, section, config::sourceName(source));
    read(s);
}

void DescriptorMatcher::Params::read(config::IniSection& s) {
    maxDistance = s.getInt("match_max_distance", maxDistance);
    ratio = s.getDouble("match_ratio", ratio);
    crossCheck = s.getBool("match_cross_check", crossCheck);
    if (maxDistance < 1 || maxDistance > 256) s.fail("match_max_distance", "must be 1..256");
    if (ratio < 0 || ratio >= 1) s.fail("match_ratio", "must be in [0, 1) (0: off)");
}

void DescriptorMatcher::Params::dumpToTextStream(std::ostream& out) const {
    out << "match_max_distance = " << maxDistance << "  [bits]\n"
        << "match_ratio        = " << ratio << "  (0: off)\n"
        << "match_cross_check  = " << (crossCheck ? "true" : "false") << "\n";
}

DescriptorMatcher::DescriptorMatcher() : DescriptorMatcher(Params()) {}

DescriptorMatcher::DescriptorMatcher(const Params& params) : params_(params) {}

std::vector<cv::DMatch> DescriptorMatcher::match(const cv::Mat& query, const cv::Mat& train) const {
    std::vector<cv::DMatch> out;
    if (query.empty() || train.empty()) return out;
    if (query.type() == CV_8U && train.type() == CV_8U && query.cols == train.cols &&
        query.cols % 8 == 0) {
        return matchPacked(query, train);
    }
    return matchWithOpenCv(query, train);
}

std::vector<cv::DMatch> DescriptorMatcher::matchPacked(const cv::Mat& query,
                                                       const cv::Mat& train) const {
    const auto h = detail::hammingBest(query, train);
    std::vector<cv::DMatch> out;
    for (int i = 0; i < query.rows; ++i) {
        const auto k = static_cast<std::size_t>(i);
        const int j = h.best[k];
        if (j < 0 || h.bestDistance[k] > params_.maxDistance) continue;
        if (params_.ratio > 0 && h.secondDistance[k] != INT_MAX &&
            h.bestDistance[k] >= params_.ratio * h.secondDistance[k]) {
            continue;
        }
        if (params_.crossCheck && h.reverseBest[static_cast<std::size_t>(j)] != i) continue;
        out.emplace_back(i, j, static_cast<float>(h.bestDistance[k]));
    }
    return out;
}

std::vector<cv::DMatch> DescriptorMatcher::matchWithOpenCv(const cv::Mat& query,
                                                           const cv::Mat& train) const {
    std::vector<cv::DMatch> out;
    if (params_.ratio <= 0) {
        // OpenCV's cross-checked brute force does exactly the mutual-best part.
        cv::BFMatcher matcher(cv::NORM_HAMMING, params_.crossCheck);
        std::vector<cv::DMatch> all;
        matcher.match(query, train, all);
        for (const auto& m : all) {
            if (m.distance <= params_.maxDistance) out.push_back(m);
        }
        return out;
    }
    // Ratio test: two nearest neighbours forward; the cross-check from the reverse best match.
    cv::BFMatcher matcher(cv::NORM_HAMMING, false);
    std::vector<std::vector<cv::DMatch>> knn;
    matcher.knnMatch(query, train, knn, 2);
    std::vector<int> reverse;
    if (params_.crossCheck) {
        std::vector<cv::DMatch> back;
        matcher.match(train, query, back);
        reverse.assign(static_cast<std::size_t>(train.rows), -1);
        for (const auto& m : back) reverse[static_cast<std::size_t>(m.queryIdx)] = m.trainIdx;
    }
    for (const auto& k : knn) {
        if (k.empty() || k[0].distance > params_.maxDistance) continue;
        if (k.size() > 1 && k[0].distance >= params_.ratio * k[1].distance) continue;
        if (params_.crossCheck &&
            reverse[static_cast<std::size_t>(k[0].trainIdx)] != k[0].queryIdx) {
            continue;
        }
        out.push_back(k[0]);
    }
    return out;
}

}  // namespace lodestone::vision
