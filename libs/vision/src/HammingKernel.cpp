#include "HammingKernel.h"

#include <climits>
#include <cstring>

namespace lodestone::vision::detail {

std::vector<std::uint64_t> packed(const cv::Mat& m, int words) {
    std::vector<std::uint64_t> out(static_cast<std::size_t>(m.rows) * words);
    for (int r = 0; r < m.rows; ++r) std::memcpy(&out[static_cast<std::size_t>(r) * words], m.ptr(r), words * 8);
    return out;
}

namespace {

// Compiled twice: with the popcnt instruction, and plain for CPUs without it (the loader picks).
__attribute__((target_clones("popcnt", "default"))) void scan(
    const std::uint64_t* q, int nq, const std::uint64_t* t, int nt, int words, HammingBest& out) {
    std::vector<int> reverseDistance(static_cast<std::size_t>(nt), INT_MAX);
    for (int i = 0; i < nq; ++i) {
        const std::uint64_t* a = q + static_cast<std::size_t>(i) * words;
        int best = -1, d1 = INT_MAX, d2 = INT_MAX;
        for (int j = 0; j < nt; ++j) {
            const std::uint64_t* b = t + static_cast<std::size_t>(j) * words;
            int d = 0;
            if (words == 4) {  // ORB: 256 bits
                d = __builtin_popcountll(a[0] ^ b[0]) + __builtin_popcountll(a[1] ^ b[1]) +
                    __builtin_popcountll(a[2] ^ b[2]) + __builtin_popcountll(a[3] ^ b[3]);
            } else {
                for (int w = 0; w < words; ++w) d += __builtin_popcountll(a[w] ^ b[w]);
            }
            if (d < d1) {
                d2 = d1;
                d1 = d;
                best = j;
            } else if (d < d2) {
                d2 = d;
            }
            if (d < reverseDistance[static_cast<std::size_t>(j)]) {
                reverseDistance[static_cast<std::size_t>(j)] = d;
                out.reverseBest[static_cast<std::size_t>(j)] = i;
            }
        }
        out.best[static_cast<std::size_t>(i)] = best;
        out.bestDistance[static_cast<std::size_t>(i)] = d1;
        out.secondDistance[static_cast<std::size_t>(i)] = d2;
    }
}

}  // namespace

HammingBest hammingBest(const cv::Mat& query, const cv::Mat& train) {
    CV_Assert(query.type() == CV_8U && train.type() == CV_8U && query.cols == train.cols &&
              query.cols % 8 == 0);
    const int words = query.cols / 8;
    HammingBest out;
    out.best.assign(static_cast<std::size_t>(query.rows), -1);
    out.bestDistance.assign(static_cast<std::size_t>(query.rows), INT_MAX);
    out.secondDistance.assign(static_cast<std::size_t>(query.rows), INT_MAX);
    out.reverseBest.assign(static_cast<std::size_t>(train.rows), -1);
    const auto q = packed(query, words), t = packed(train, words);
    scan(q.data(), query.rows, t.data(), train.rows, words, out);
    return out;
}

}  // namespace lodestone::vision::detail
