#pragma once

#include <cstddef>
#include <optional>
#include <vector>

namespace lodestone::magnetic {

/** A supernode of the current path matched to a stored one (eq. 2 cost). */
struct SupernodeMatch {
    std::size_t query{0}, target{0};  ///< supernode IDs
    double offset{0};                 ///< target travel - query travel at their first samples [m]
    double cost{0};                   ///< RMS [uT]
};

/** Consecutive query supernodes matched to target supernodes that follow each other the same
 * way: the same stretch of path driven again (paper 000 Fig. 2, a node bundle). */
struct BundleMatch {
    std::size_t firstQuery{0}, lastQuery{0};  ///< supernode IDs (inclusive)
    std::size_t firstTarget{0}, lastTarget{0};
    double offset{0};       ///< target travel - query travel [m] at the last match
    std::size_t length{0};  ///< supernode matches in the chain
    double meanCost{0};
};

/** Node-bundle matching (paper 000 §2.2): supernode matches are links of a connection graph;
 * a query supernode's match extends a chain when the previous query supernode matched a
 * target at about the same travel offset (within `offsetTolerance`, which absorbs odometry
 * scale error). A chain of `minChain` links is a bundle match. Several live chains may
 * qualify at once: the same place visited several times before (all right), or places that
 * look alike (aliasing); which it is takes the map, so the caller decides (see
 * MagneticGpERD). */
class BundleMatcher {
  public:
    struct Params {
        std::size_t minChain{3};
        double offsetTolerance{0.3};  ///< [m]
    };
    struct Stats {
        std::size_t queries{0}, matched{0}, bundles{0};  ///< bundles: queries with one or more
    };

    explicit BundleMatcher(const Params& params) : params_(params) {}

    /** The candidate matches of query supernode `query` (any order; empty: no match). A
     * `query` that does not follow the previous one (a kidnap broke the path) ends every
     * chain. Returns the bundles the query completes or extends, cheapest first. */
    std::vector<BundleMatch> add(std::size_t query, const std::vector<SupernodeMatch>& candidates,
                                 bool followsPrevious);

    const Stats& stats() const { return stats_; }
    const Params& params() const { return params_; }

  private:
    struct Chain {
        BundleMatch m;
        double costSum{0};
    };
    Params params_;
    std::vector<Chain> chains_;
    Stats stats_;
};

}  // namespace lodestone::magnetic
