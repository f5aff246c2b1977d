#include <lodestone/odometry/CovarianceWeightedFusion.h>
#include <lodestone/odometry/KalmanFusion.h>
#include <lodestone/odometry/PlanarFusion.h>

#include <stdexcept>

namespace lodestone::odometry {

namespace {
constexpr double kUnknownMotionVariance = 1.0;  // [m^2, rad^2]: a step VO could not see

// One source alone: the wheels, or VO (standing still while it has nothing).
class SingleSourceFusion : public PlanarFusion {
  public:
    explicit SingleSourceFusion(bool visual) : visual_(visual) {}
    const mrpt::poses::CPosePDFGaussian& step(const OdometryStep& s) override {
        wheel_gain_ = (visual_ ? 0.0 : 1.0) * Eigen::Matrix3d::Identity();
        if (!visual_) {
            increment_ = s.wheel;
        } else if (s.visual) {
            increment_ = *s.visual;
        } else {
            // Standing still for lack of a measurement: no motion, but no confidence either.
            increment_ = mrpt::poses::CPosePDFGaussian();
            increment_.cov.setDiagonal(3, kUnknownMotionVariance);
        }
        pose_ += increment_;
        return pose_;
    }
    const mrpt::poses::CPosePDFGaussian& pose() const override { return pose_; }
    void reset(const mrpt::poses::CPosePDFGaussian& start) override { pose_ = start; }
    std::string name() const override { return visual_ ? "visual" : "wheel"; }

  private:
    bool visual_;
    mrpt::poses::CPosePDFGaussian pose_;
};
}  // namespace

std::unique_ptr<PlanarFusion> makePlanarFusion(const std::string& method, double kalmanWeight,
                                               double kalmanProcessNoise,
                                               double kalmanMeasurementNoise) {
    if (method == "wheel") return std::make_unique<SingleSourceFusion>(false);
    if (method == "visual") return std::make_unique<SingleSourceFusion>(true);
    if (method == "covariance") return std::make_unique<CovarianceWeightedFusion>();
    if (method == "kalman") {
        return std::make_unique<KalmanFusion>(kalmanWeight, kalmanProcessNoise,
                                              kalmanMeasurementNoise);
    }
    throw std::invalid_argument("unknown odometry fusion method '" + method +
                                "' (wheel, visual, covariance, kalman)");
}

}  // namespace lodestone::odometry
