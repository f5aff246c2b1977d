#pragma once

#include <cstdint>
#include <vector>

namespace lodestone::sim {

/** A small, fully specified pseudo-random generator (xoshiro256**, seeded by splitmix64) with
 * its own uniform and normal draws. std:: distributions are implementation-defined; these give
 * the same numbers on every platform, so a scenario and a seed always give the same rawlog. */
class Random {
  public:
    explicit Random(std::uint64_t seed);

    std::uint64_t nextU64();
    double uniform();                      ///< [0, 1)
    double uniform(double lo, double hi);  ///< [lo, hi)
    int uniformInt(int lo, int hiInclusive);
    double normal();  ///< N(0, 1), Box–Muller
    double normal(double mean, double std);

    /** A generator for a sub-stream (e.g. one sensor), independent of how much this one is
     * used later. */
    Random fork(std::uint64_t streamId) const;

  private:
    std::uint64_t s_[4];
    std::uint64_t seed_;
    double spare_{0};
    bool has_spare_{false};
};

/** A fixed table of N(0,1) samples read from a moving offset: per-pixel image noise at the
 * cost of an array read. */
class NoiseTable {
  public:
    NoiseTable(std::uint64_t seed, std::size_t size = 1 << 20);
    /** A start offset for one frame. */
    std::size_t randomOffset(Random& rng) const;
    /** Sample `i` after `offset` (wraps). */
    float at(std::size_t offset, std::size_t i) const { return table_[(offset + i) & mask_]; }

  private:
    std::vector<float> table_;
    std::size_t mask_;
};

}  // namespace lodestone::sim
