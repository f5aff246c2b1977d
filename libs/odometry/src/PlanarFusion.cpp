#include <lodestone/odometry/CovarianceWeightedFusion.h>
#include <lodestone/odometry/KalmanFusion.h>
#include <lodestone/odometry/PlanarFusion.h>

#include <stdexcept>

namespace lodestone::odometry {

namespace {
// One source alone: the wheels, or VO (standing still while it has nothing).
class SingleSourceFusion : public PlanarFusion {
  public:
    explicit SingleSourceFusion(bool visual) : visual_(visual) {}
    const mrpt::poses::CPosePDFGaussian& step(const OdometryStep& s) override {
        if (!visual_) {
            pose_ += s.wheel;
        } else if (s.visual) {
            pose_ += *s.visual;
        }
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
