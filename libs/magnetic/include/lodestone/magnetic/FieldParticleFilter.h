#pragma once

#include <lodestone/magnetic/PlanarFieldGrid.h>

#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <memory>
#include <random>
#include <vector>

namespace lodestone::magnetic {

struct FieldParticleFilterParams {
    std::size_t particles{100000};
    /** Particles while the cloud holds one place (0: a twentieth of `particles`): a converged
     * cloud spans a few cells, and the global count would cost twenty times as much to follow
     * it. Back to `particles` at the next resampling once it no longer holds one place. */
    std::size_t trackingParticles{0};
    /** [uT] per component: what a later pass reads beyond what the map predicts and the
     * reading noise - another day's disturbances, a magnetometer mounted a little apart. Two
     * passes of one place differ by 0.5-0.8 uT on Kok's walks and by 1.2-4 uT between Aalto's
     * trials; the filter's result changed little between 1 and 5 uT there. */
    double passSigma{1.0};
    /** Degrees of freedom of a Student-t residual (0: Gaussian). */
    double tailDof{0};
    /** [m] travel between two weighings: readings closer than the field's length scale
     * repeat each other's errors (another day's disturbance is a field too), and weighing
     * each as new evidence makes the cloud collapse on a look-alike. 0: the length scale. */
    double updateSpacing{0};
    /** Converged - one place, not several: the cloud's largest position sigma [m] below this
     * (0: half the field's length scale, over which the field decorrelates) and its heading
     * sigma [rad] below `convergedYawSigma`. How precisely the place is known is the
     * covariance, not this test. */
    double convergedSigma{0};
    double convergedYawSigma{5 * M_PI / 180};
    double resampleShare{0.5};  ///< resample when the effective sample size drops below
    std::uint64_t seed{1};
};

/** Where the robot is in a field map, from nothing: Monte Carlo localization over (x, y, yaw)
 * with the map's field as the only measurement. Particles start spread over the map's band in
 * every heading; odometry moves each with its own draw of the odometry noise; each weighing
 * compares the reading (levelled robot frame, turned by the particle's heading) with the
 * map's prediction at the particle, under the map's variance plus the reading noise plus
 * `passSigma`^2 (off the band: the prior - a place the map does not know explains a reading
 * no better than the field's spread). This is what the sequence matchers cannot do: it places
 * a pass that crosses the mapped paths instead of following one of them, either way. */
class FieldParticleFilter {
  public:
    using Params = FieldParticleFilterParams;
    FieldParticleFilter(std::shared_ptr<const PlanarFieldGrid> map, const Params& p = {});

    /** Particles spread uniformly over the band, any heading; weights equal. */
    void reset();
    /** The robot moved by `delta` (dx, dy in the frame of its previous pose, dyaw) with
     * odometry covariance `cov` (3 x 3, same order). Motions are compounded (their covariance
     * to first order) and drawn for the particles once, before the next weighing: the cost
     * goes with the weighings, not with the odometry's rate. */
    void move(const Eigen::Vector3d& delta, const Eigen::Matrix3d& cov);
    /** A reading in the levelled robot frame [uT]. Weighs the particles with it if the robot
     * travelled `updateSpacing` since the last weighing (returns whether it did); a reading
     * that is not finite is ignored. */
    bool measure(const Eigen::Vector3d& robotField);

    /** The cloud's weighted mean and covariance at the last weighing, carried on by the
     * motion since. */
    struct Estimate {
        Eigen::Vector3d pose{Eigen::Vector3d::Zero()};  ///< x, y, yaw (weighted; circular yaw)
        Eigen::Matrix3d covariance{Eigen::Matrix3d::Identity()};
        double effectiveShare{1};  ///< effective sample size / particles
        bool converged{false};
    };
    Estimate estimate() const;
    std::size_t weighings() const { return weighings_; }
    /** [m] the position sigma below which the cloud holds one place (convergedSigma, or half
     * the length scale). */
    double convergedSigma() const { return converged_sigma_; }

  private:
    void applyMotion();
    void resample(std::size_t n);
    Estimate cloud() const;

    std::shared_ptr<const PlanarFieldGrid> map_;
    Params params_;
    double spacing_{0}, converged_sigma_{0};
    std::mt19937_64 rng_;
    std::vector<double> x_, y_, yaw_, logw_;
    std::vector<double> variance_, log_variance_;  ///< of a residual, per map cell (last: off it)
    Eigen::Vector3d pending_{Eigen::Vector3d::Zero()};
    Eigen::Matrix3d pending_cov_{Eigen::Matrix3d::Zero()};
    Estimate cloud_;
    double travel_since_{0};
    std::size_t weighings_{0};
};

}  // namespace lodestone::magnetic
