#include <lodestone/vision/BinaryWordIndex.h>

#include <algorithm>
#include <numeric>
#include <random>
#include <stdexcept>

namespace lodestone::vision {

BinaryWordIndex::BinaryWordIndex() : BinaryWordIndex(Params{}) {}

BinaryWordIndex::BinaryWordIndex(Params params) : params_(params) {
    if (params_.tables < 1 || params_.bits < 1 || params_.bits > 24) {
        throw std::invalid_argument("BinaryWordIndex: tables >= 1 and bits in [1, 24]");
    }
    std::mt19937_64 rng(params_.seed);
    std::vector<int> all(256);
    std::iota(all.begin(), all.end(), 0);
    for (int t = 0; t < params_.tables; ++t) {
        std::shuffle(all.begin(), all.end(), rng);
        bit_positions_.emplace_back(all.begin(), all.begin() + params_.bits);
    }
    tables_.resize(static_cast<std::size_t>(params_.tables));
    for (auto& t : tables_) {
        t.head.assign(std::size_t{1} << params_.bits, 0);
        t.count.assign(std::size_t{1} << params_.bits, 0);
    }
}

std::uint32_t BinaryWordIndex::key(const std::uint8_t* d, int table) const {
    std::uint32_t k = 0;
    for (const int bit : bit_positions_[static_cast<std::size_t>(table)]) {
        k = (k << 1) | ((d[bit >> 3] >> (bit & 7)) & 1u);
    }
    return k;
}

void BinaryWordIndex::add(std::uint32_t place, const cv::Mat& descriptors) {
    if (!descriptors.empty() && (descriptors.type() != CV_8U || descriptors.cols != 32)) {
        throw std::invalid_argument("BinaryWordIndex: descriptors must be 32-byte binary rows");
    }
    const int n = std::min(descriptors.rows, params_.wordsPerPlace);
    for (int ti = 0; ti < params_.tables; ++ti) {
        Table& t = tables_[static_cast<std::size_t>(ti)];
        for (int i = 0; i < n; ++i) {
            const std::uint32_t k = key(descriptors.ptr<std::uint8_t>(i), ti);
            // One entry per place and key: a place votes once per matching word.
            if (t.head[k] && t.place[t.head[k] - 1] == place) continue;
            t.place.push_back(place);
            t.next.push_back(t.head[k]);
            t.head[k] = static_cast<std::uint32_t>(t.place.size());
            ++t.count[k];
        }
    }
    max_place_ = std::max(max_place_, place);
    ++places_;
}

std::vector<std::pair<std::uint32_t, int>> BinaryWordIndex::query(const cv::Mat& descriptors,
                                                                  std::size_t top) const {
    if (votes_.size() <= max_place_) votes_.resize(max_place_ + 1, 0);
    std::vector<std::uint32_t> touched;
    for (int ti = 0; ti < params_.tables; ++ti) {
        const Table& t = tables_[static_cast<std::size_t>(ti)];
        for (int i = 0; i < descriptors.rows; ++i) {
            const std::uint32_t k = key(descriptors.ptr<std::uint8_t>(i), ti);
            if (t.count[k] == 0 || t.count[k] > params_.maxBucket) continue;
            for (std::uint32_t e = t.head[k]; e; e = t.next[e - 1]) {
                const std::uint32_t p = t.place[e - 1];
                if (votes_[p]++ == 0) touched.push_back(p);
            }
        }
    }
    std::vector<std::pair<std::uint32_t, int>> out;
    out.reserve(touched.size());
    for (const std::uint32_t p : touched) {
        out.emplace_back(p, votes_[p]);
        votes_[p] = 0;
    }
    const std::size_t n = std::min(top, out.size());
    std::partial_sort(out.begin(), out.begin() + static_cast<std::ptrdiff_t>(n), out.end(),
                      [](const auto& a, const auto& b) {
                          return a.second != b.second ? a.second > b.second : a.first < b.first;
                      });
    out.resize(n);
    return out;
}

}  // namespace lodestone::vision
