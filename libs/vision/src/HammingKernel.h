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

/** Rows packed as 64-bit words (a copy: cv::Mat rows need not be 8-byte aligned). */
std::vector<std::uint64_t> packed(const cv::Mat& m, int words);

/** The Hamming distance of two packed descriptors of `words` 64-bit words. */
inline int hammingDistance(const std::uint64_t* a, const std::uint64_t* b, int words) {
    int d = 0;
    for (int w = 0; w < words; ++w) d += __builtin_popcountll(a[w] ^ b[w]);
    return d;
}

/** Both matrices CV_8U, one descriptor per row, the same number of columns, a multiple of 8. */
HammingBest hammingBest(const cv::Mat& query, const cv::Mat& train);

}  // namespace lodestone::vision::detail
