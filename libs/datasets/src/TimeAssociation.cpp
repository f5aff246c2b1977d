#include <lodestone/datasets/TimeAssociation.h>

#include <algorithm>
#include <cmath>
#include <tuple>

namespace lodestone::datasets {

std::vector<std::pair<std::size_t, std::size_t>> associateByTime(const std::vector<double>& a,
                                                                 const std::vector<double>& b,
                                                                 double maxDt) {
    std::vector<std::tuple<double, std::size_t, std::size_t>> candidates;
    std::size_t lo = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        while (lo < b.size() && b[lo] < a[i] - maxDt) ++lo;
        for (std::size_t j = lo; j < b.size() && b[j] <= a[i] + maxDt; ++j) {
            candidates.emplace_back(std::abs(b[j] - a[i]), i, j);
        }
    }
    std::sort(candidates.begin(), candidates.end());
    std::vector<char> usedA(a.size(), 0), usedB(b.size(), 0);
    std::vector<std::pair<std::size_t, std::size_t>> out;
    for (const auto& [d, i, j] : candidates) {
        if (usedA[i] || usedB[j]) continue;
        usedA[i] = usedB[j] = 1;
        out.emplace_back(i, j);
    }
    std::sort(out.begin(), out.end());
    return out;
}

}  // namespace lodestone::datasets
