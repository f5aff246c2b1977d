#pragma once

#include <lodestone/magnetic/DistanceResampler.h>

#include <Eigen/Core>
#include <cstddef>
#include <utility>
#include <vector>

namespace lodestone::magnetic {

/** One distance-resampled point of the field along the robot's path. */
struct TrackSample {
    double s{0};            ///< travel since the start [m] (keeps growing across kidnaps)
    Eigen::VectorXf value;  ///< field feature (FieldFeatures), one entry per channel
    std::size_t node{0};    ///< the graph node whose interval the point lies in
    int segment{0};         ///< continuous-odometry segment (kidnaps break the path)
};

/** Paper 000's supernode: the field over `length` metres of path as one vector, cost-compared
 * by L2 distance (eq. 2). Supernodes overlap (a new one every `stride` metres, Fig. 2), so a
 * revisit lines up with one of them within stride / 2 whatever the phase of the visits. */
struct Supernode {
    std::size_t id{0};
    std::size_t first{0}, last{0};  ///< track samples [first, last)
    Eigen::VectorXf vector;         ///< samples x channels, sample-major, mean removed per channel
    Eigen::VectorXf mean;           ///< per-channel mean [uT] (kept apart: it carries no shape)
    float spread{0};                ///< largest per-channel standard deviation [uT]
    int segment{0};
};

/** The path's field as distance-resampled samples, cut into overlapping supernodes. Readings
 * come in travel order with the node they belong to; a new segment (after a kidnap) restarts
 * the resampling so that no supernode spans the break. */
class SupernodeTrack {
  public:
    struct Params {
        double step{0.05};    ///< resampling interval [m]
        double length{2.0};   ///< supernode length [m]
        double stride{0.25};  ///< a new supernode every this much travel [m]
    };

    SupernodeTrack(const Params& params, int channels);
    /** One reading at travel `s` on `segment` in node `node`'s interval. Returns the
     * supernodes it completed (usually none, at most a few). */
    std::vector<Supernode> add(double s, const Eigen::VectorXd& feature, std::size_t node,
                               int segment);

    const Params& params() const { return params_; }
    int channels() const { return channels_; }
    std::size_t samplesPerSupernode() const { return per_supernode_; }
    const std::vector<TrackSample>& samples() const { return samples_; }
    const std::vector<Supernode>& supernodes() const { return supernodes_; }

    /** The L2 cost of eq. (2) between two supernodes' shape vectors, as an RMS per element
     * [uT] so that it reads the same for any length; +inf when their sizes differ. */
    static float cost(const Supernode& a, const Supernode& b);

    /** cost() of `q` against the stored samples [first, first + samplesPerSupernode()), mean
     * removed as a supernode's are; +inf when that window leaves the track or spans two
     * segments. */
    float costAt(const Supernode& q, std::size_t first) const;
    /** Supernodes are cut every `stride`: a revisit lines up with one of them only within
     * stride / 2, and on a field that changes within decimetres that phase error alone can
     * cost more than a match may. The best costAt over `t` slid by up to `maxShift` samples
     * either way, and the first sample where it is. */
    std::pair<float, std::size_t> alignedCost(const Supernode& q, const Supernode& t,
                                              std::size_t maxShift) const;
    /** Half the stride in samples, rounded up: the slide alignedCost needs. */
    std::size_t halfStrideSamples() const { return (stride_samples_ + 1) / 2; }

  private:
    void emitIfDue(std::vector<Supernode>& out);

    Params params_;
    int channels_;
    std::size_t per_supernode_, stride_samples_;
    DistanceResampler resampler_;
    std::vector<TrackSample> samples_;
    std::vector<Supernode> supernodes_;
    std::size_t segment_start_{0};  // first sample of the current segment
    std::size_t next_end_{0};       // sample count at which the next supernode ends
    int segment_{0};
    std::size_t node_{0};
    bool started_{false};
};

}  // namespace lodestone::magnetic
