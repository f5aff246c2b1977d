#include <lodestone/magnetic/BundleMatcher.h>

#include <algorithm>
#include <cmath>

namespace lodestone::magnetic {

std::vector<BundleMatch> BundleMatcher::add(std::size_t query,
                                            const std::vector<SupernodeMatch>& candidates,
                                            bool followsPrevious) {
    ++stats_.queries;
    if (!candidates.empty()) ++stats_.matched;
    if (!followsPrevious) chains_.clear();
    std::vector<SupernodeMatch> sorted = candidates;
    std::sort(sorted.begin(), sorted.end(),
              [](const SupernodeMatch& a, const SupernodeMatch& b) { return a.cost < b.cost; });
    std::vector<Chain> next;
    std::vector<bool> used(sorted.size(), false);
    for (const auto& c : chains_) {
        if (c.m.lastQuery + 1 != query) continue;
        // The cheapest candidate at about the chain's offset extends it.
        for (std::size_t k = 0; k < sorted.size(); ++k) {
            if (used[k] || std::abs(sorted[k].offset - c.m.offset) > params_.offsetTolerance)
                continue;
            if (sorted[k].target <= c.m.lastTarget) continue;  // a chain moves forward
            Chain e = c;
            e.m.lastQuery = query;
            e.m.lastTarget = sorted[k].target;
            e.m.offset = sorted[k].offset;
            ++e.m.length;
            e.costSum += sorted[k].cost;
            e.m.meanCost = e.costSum / double(e.m.length);
            used[k] = true;
            next.push_back(e);
            break;
        }
    }
    for (std::size_t k = 0; k < sorted.size(); ++k) {
        if (used[k]) continue;
        // Candidates next to one already taken (the neighbouring overlapped supernode of the
        // same place) start no chain of their own.
        bool nearTaken = false;
        for (const auto& n : next) {
            nearTaken =
                nearTaken || std::abs(n.m.offset - sorted[k].offset) <= params_.offsetTolerance;
        }
        if (nearTaken) continue;
        Chain c;
        c.m = {query, query,         sorted[k].target, sorted[k].target, sorted[k].offset,
               1,     sorted[k].cost};
        c.costSum = sorted[k].cost;
        next.push_back(c);
    }
    chains_ = std::move(next);
    std::vector<BundleMatch> out;
    for (const auto& c : chains_) {
        if (c.m.length >= params_.minChain) out.push_back(c.m);
    }
    std::sort(out.begin(), out.end(),
              [](const BundleMatch& a, const BundleMatch& b) { return a.meanCost < b.meanCost; });
    if (!out.empty()) ++stats_.bundles;
    return out;
}

}  // namespace lodestone::magnetic
