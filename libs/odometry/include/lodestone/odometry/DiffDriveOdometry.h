#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <mrpt/poses/CPosePDFGaussian.h>

#include <Eigen/Core>

#include <cstdint>
#include <optional>

namespace lodestone::odometry {

/** Dead reckoning of a differential-drive base from wheel encoder ticks, exactly as paper 003
 * eq. (1): with wheel travels Δs_l, Δs_r and wheel base b,
 *   x' = x + (Δs_r + Δs_l)/2 cos(Φ + (Δs_r − Δs_l)/(2b)),
 *   y' = y + (Δs_r + Δs_l)/2 sin(Φ + (Δs_r − Δs_l)/(2b)),   Φ' = Φ + (Δs_r − Δs_l)/b,
 * with the covariance propagated from per-wheel noise: each wheel's travel has variance
 * k |Δs| (errors grow with distance, as slip does), mapped through the Jacobian of eq. (1). */
class DiffDriveOdometry {
  public:
    struct Params : public mrpt::config::CLoadableOptions {
        double wheelBase{0.23};       ///< distance between the wheel contact points [m]
        double wheelRadius{0.035};    ///< [m]
        double ticksPerRev{2578.33};  ///< encoder ticks per wheel revolution
        double wheelNoise{4e-4};      ///< variance per metre of wheel travel, k [m^2/m]

        void loadFromConfigFile(const mrpt::config::CConfigFileBase& source,
                                const std::string& section) override;
        void dumpToTextStream(std::ostream& out) const override;
    };

    /** One step of eq. (1): the motion in the frame of the pose before it, with covariance. */
    struct Increment {
        mrpt::poses::CPosePDFGaussian motion;
        double leftTravel{0}, rightTravel{0};  ///< [m]
    };

    DiffDriveOdometry();
    explicit DiffDriveOdometry(const Params& params);

    /** Starts (or restarts) integrating at `pose`. The next tick reading is the reference. */
    void reset(const mrpt::poses::CPosePDFGaussian& pose = {});

    /** Absolute encoder counts (as CObservationOdometry carries them). The first reading after
     * reset() only sets the reference and returns nullopt. 32-bit counter wrap-around is
     * handled. */
    std::optional<Increment> addTicks(std::int32_t leftTicks, std::int32_t rightTicks);

    /** Wheel travels since the last step [m]. */
    Increment addTravel(double leftTravel, double rightTravel);

    /** The integrated pose and its covariance. */
    const mrpt::poses::CPosePDFGaussian& pose() const { return pose_; }
    const Params& params() const { return params_; }

    /** Eq. (1) and its covariance for one step from the origin, for tests and fusion. */
    static mrpt::poses::CPosePDFGaussian stepFromOrigin(double leftTravel, double rightTravel,
                                                        const Params& params);

    /** How that step's (x, y, phi) moves with each wheel's scale: the derivative with respect
     * to (e_l, e_r) where the true travels are Δs_l (1 + e_l), Δs_r (1 + e_r), at e = 0. An
     * uncalibrated wheel radius is such a scale: the same every step, so its heading error
     * grows with distance instead of averaging out (what a graph can estimate, not absorb). */
    static Eigen::Matrix<double, 3, 2> scaleJacobian(double leftTravel, double rightTravel,
                                                     const Params& params);

    /** The scale Jacobian of a composed motion `before` (+) `step`, from those of its parts
     * (each in its own (x, y, phi)): first-order propagation through the composition. */
    static Eigen::Matrix<double, 3, 2> composeScaleJacobian(
        const mrpt::poses::CPose2D& before, const Eigen::Matrix<double, 3, 2>& beforeJacobian,
        const mrpt::poses::CPose2D& step, const Eigen::Matrix<double, 3, 2>& stepJacobian);

  private:
    Params params_;
    mrpt::poses::CPosePDFGaussian pose_;
    std::optional<std::pair<std::int32_t, std::int32_t>> last_ticks_;
};

}  // namespace lodestone::odometry
