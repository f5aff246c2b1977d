#pragma once

#include <utility>
#include <vector>

namespace lodestone::datasets {

/** Pairs (i, j) of `a[i]` and `b[j]` timestamps at most `maxDt` apart, closest first, each
 * element used once, sorted by i — the association of the TUM RGB-D tools (associate.py).
 * Both inputs must be sorted ascending. */
std::vector<std::pair<std::size_t, std::size_t>> associateByTime(const std::vector<double>& a,
                                                                 const std::vector<double>& b,
                                                                 double maxDt);

}  // namespace lodestone::datasets
