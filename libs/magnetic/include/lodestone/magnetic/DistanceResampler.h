#pragma once

#include <Eigen/Core>
#include <optional>
#include <vector>

namespace lodestone::magnetic {

/** Turns readings taken in time into readings spaced in distance: the field along the path,
 * sampled every `step` metres of travel, independent of how fast the robot went (paper 000's
 * supernodes are sequences over distance). Each output is the mean of the readings whose
 * travel falls in its bin; an empty bin (fast motion, sparse readings) is filled by linear
 * interpolation between its neighbours. */
class DistanceResampler {
  public:
    struct Sample {
        double s{0};  ///< travel at the bin centre [m]
        Eigen::VectorXd value;
    };

    explicit DistanceResampler(double step);
    /** A reading at travel `s` (non-decreasing between resets). Returns the bins it completed. */
    std::vector<Sample> add(double s, const Eigen::VectorXd& value);
    /** Forget the open bin (a kidnap: the path is broken). */
    void reset();
    double step() const { return step_; }

  private:
    double step_;
    std::optional<long> bin_;  // index of the open bin
    Eigen::VectorXd sum_;
    int count_{0};
    std::optional<Sample> last_;  // last emitted, for interpolation across empty bins
};

}  // namespace lodestone::magnetic
