#pragma once
// The Hamming distances between two sets of binary descriptors, with the best (and second
// best) match of each row and the best row of each column, in one pass over the pair matrix:
// 64-bit words, XOR and popcount (the CPU's instruction where it has one). What cv::BFMatcher
// does with NORM_HAMMING, without a library call and its bookkeeping per pair.

#include <opencv2/core.hpp>

#include <cstdint>
#include <vector>

namespace lodestone::vision::detail {

struct HammingBest {
    /** Per query row: best train index (-1 if none), its distance, the second-best distance
     * (INT_MAX if none). Ties keep the lowest index, as OpenCV does. */
    std::vector<int> best, bestDistance, secondDistance;
    /** Per train row: the query row nearest to it (lowest index on ties), -1 if none. */
    std::vector<int> reverseBest;
};

/** Both matrices CV_8U, one descriptor per row, the same number of columns, a multiple of 8. */
HammingBest hammingBest(const cv::Mat& query, const cv::Mat& train);

}  // namespace lodestone::vision::detail
