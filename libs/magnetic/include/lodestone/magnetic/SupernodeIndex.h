#pragma once

#include <lodestone/magnetic/SupernodeTrack.h>

#include <memory>
#include <vector>

namespace lodestone::magnetic {

/** Nearest supernodes by field, sublinear in how many are stored: a KD-tree (nanoflann,
 * dynamic) over a short summary of each supernode (its raw field averaged into `bins` bins per
 * channel), so that a query costs a tree descent, not a scan. The summary only shortlists; the
 * caller ranks the shortlist by the full eq. (2) cost. */
class SupernodeIndex {
  public:
    SupernodeIndex(int channels, std::size_t samplesPerSupernode, int bins = 8);
    ~SupernodeIndex();
    SupernodeIndex(const SupernodeIndex&) = delete;
    SupernodeIndex& operator=(const SupernodeIndex&) = delete;

    void add(const Supernode& s);
    std::size_t size() const;
    /** Up to `k` stored supernode IDs nearest to `s` in summary space, nearest first. */
    std::vector<std::size_t> nearest(const Supernode& s, std::size_t k) const;
    /** The summary of a supernode (exposed for tests). */
    std::vector<float> summary(const Supernode& s) const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace lodestone::magnetic
