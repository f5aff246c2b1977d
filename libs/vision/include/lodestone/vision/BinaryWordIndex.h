#pragma once

#include <opencv2/core.hpp>

#include <cstdint>
#include <utility>
#include <vector>

namespace lodestone::vision {

/** An appearance index over places (e.g. submaps): locality-sensitive hashing of 256-bit ORB
 * descriptors. Each of `tables` tables keys a descriptor by `bits` of its bits, drawn at random
 * (seeded), so two descriptors a few bits apart share a key in some table; a place that holds
 * many descriptors close to the query's collects many votes. A look-up costs what the visited
 * buckets hold, not the number of places; over-full buckets (words everywhere, like the
 * descriptors of a plain wall) are ignored, as a text index ignores stop words. */
class BinaryWordIndex {
  public:
    struct Params {
        int tables{4};
        int bits{20};  ///< key length, at most 24 (the tables are direct-addressed)
        int wordsPerPlace{300};  ///< descriptors indexed per place, the first ones given
        std::size_t maxBucket{2000};  ///< buckets fuller than this do not vote
        std::uint64_t seed{7};
    };

    BinaryWordIndex();
    explicit BinaryWordIndex(Params params);

    /** Indexes up to wordsPerPlace rows of `descriptors` (CV_8U, 32 bytes each) for `place`.
     * Places are added once each. */
    void add(std::uint32_t place, const cv::Mat& descriptors);
    /** Places sharing words with `descriptors`, most votes first, at most `top`. */
    std::vector<std::pair<std::uint32_t, int>> query(const cv::Mat& descriptors,
                                                     std::size_t top) const;
    std::size_t places() const { return places_; }

  private:
    std::uint32_t key(const std::uint8_t* descriptor, int table) const;

    /** One hash table, direct-addressed: head[key] starts a chain through the entry arrays
     * (compact, so a look-up touches little memory however many places there are). */
    struct Table {
        std::vector<std::uint32_t> head;   // per key: first entry + 1 (0: empty)
        std::vector<std::uint32_t> count;  // per key: entries in the chain
        std::vector<std::uint32_t> place, next;  // per entry; next = following entry + 1
    };

    Params params_;
    std::vector<std::vector<int>> bit_positions_;  // per table
    std::vector<Table> tables_;
    std::size_t places_{0};
    std::uint32_t max_place_{0};
    mutable std::vector<int> votes_;  // scratch, all zero between queries
};

}  // namespace lodestone::vision
