#include <lodestone/vision/BinaryWordIndex.h>

#include <algorithm>
#include <numeric>
#include <random>
#include <stdexcept>

namespace lodestone::vision {

BinaryWordIndex::BinaryWordIndex() : BinaryWordIndex(Params{}) {}

BinaryWordIndex::BinaryWordIndex(Params params) : params_(params) {
    if (params_.tables < 1 || params_.bits < 1 || params_.bits > 32) {
        throw std::invalid_argument("BinaryWordIndex: tables >= 1 and bits in [1, 32]");
    }
    std::mt19937_64 rng(params_.seed);
    std::vector<int> all(256);
    std::iota(all.begin(), all.end(), 0);
    for (int t = 0; t < params_.tables; ++t) {
        std::shuffle(all.begin(), all.end(), rng);
        bit_positions_.emplace_back(all.begin(), all.begin() + params_.bits);
    }
    tables_.resize(static_cast<std::size_t>(params_.tables));
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
    for (int t = 0; t < params_.tables; ++t) {
        auto& table = tables_[static_cast<std::size_t>(t)];
        for (int i = 0; i < n; ++i) {
            auto& bucket = table[key(descriptors.ptr<std::uint8_t>(i), t)];
            if (bucket.empty() || bucket.back() != place) bucket.push_back(place);
        }
    }
    ++places_;
}

std::vector<std::pair<std::uint32_t, int>> BinaryWordIndex::query(const cv::Mat& descriptors,
                                                                  std::size_t top) const {
    std::unordered_map<std::uint32_t, int> votes;
    for (int t = 0; t < params_.tables; ++t) {
        const auto& table = tables_[static_cast<std::size_t>(t)];
        for (int i = 0; i < descriptors.rows; ++i) {
            const auto it = table.find(key(descriptors.ptr<std::uint8_t>(i), t));
            if (it == table.end() || it->second.size() > params_.maxBucket) continue;
            for (const std::uint32_t place : it->second) ++votes[place];
        }
    }
    std::vector<std::pair<std::uint32_t, int>> out(votes.begin(), votes.end());
    const std::size_t n = std::min(top, out.size());
    std::partial_sort(out.begin(), out.begin() + static_cast<std::ptrdiff_t>(n), out.end(),
                      [](const auto& a, const auto& b) {
                          return a.second != b.second ? a.second > b.second : a.first < b.first;
                      });
    out.resize(n);
    return out;
}

}  // namespace lodestone::vision
