#include <lodestone/odometry/GyroBiasEstimator.h>

#include <cmath>

namespace lodestone::odometry {

bool GyroBiasEstimator::update(const Eigen::Matrix3d& gyro, const Eigen::Matrix3d& measured,
                               double measuredSigma, double seconds) {
    if (!(seconds > 0) || !(measuredSigma >= 0)) return false;
    // With a bias b left in the rates, the gyro's rotation is the true one turned on by
    // exp(b T) in its own frame (first order): what the other sensor's leaves over, per second.
    const Eigen::AngleAxisd d(measured.transpose() * gyro);
    const Eigen::Vector3d residual = d.angle() * d.axis() / seconds;
    const double noise = measuredSigma * measuredSigma / (seconds * seconds);
    constexpr double kChi2Rotation999 = 16.266;  // chi-square, 3 dof, 99.9 %
    if (residual.squaredNorm() / (variance_ + noise) > kChi2Rotation999) {
        ++skipped_;
        return false;
    }
    const double gain = variance_ / (variance_ + noise);
    bias_ += gain * residual;
    variance_ *= 1 - gain;
    ++updates_;
    return true;
}

double GyroBiasEstimator::sigma() const { return std::sqrt(variance_); }

}  // namespace lodestone::odometry
