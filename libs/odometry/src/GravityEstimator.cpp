#include <lodestone/odometry/GravityEstimator.h>
#include <mrpt/system/datetime.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace lodestone::odometry {

bool GravityEstimator::add(const mrpt::obs::CObservationIMU& imu) {
    using namespace mrpt::obs;
    for (const auto k : {IMU_WX, IMU_WY, IMU_WZ, IMU_X_ACC, IMU_Y_ACC, IMU_Z_ACC}) {
        if (!imu.has(k)) return false;
    }
    const Eigen::Vector3d w(imu.get(IMU_WX), imu.get(IMU_WY), imu.get(IMU_WZ));
    const Eigen::Vector3d f(imu.get(IMU_X_ACC), imu.get(IMU_Y_ACC), imu.get(IMU_Z_ACC));
    const double t = mrpt::Clock::toDouble(imu.timestamp);
    if (!w.allFinite() || !f.allFinite() || !std::isfinite(t)) return false;
    if (!samples_.empty() && t <= samples_.back().t) return false;
    samples_.push_back({t, w, f});
    sensor_on_robot_.matrix() =
        imu.sensorPose.getHomogeneousMatrixVal<mrpt::math::CMatrixDouble44>().asEigen();
    return true;
}

std::optional<GravityEstimator::Up> GravityEstimator::at(double t,
                                                         const Eigen::Vector3d& meanAcceleration,
                                                         double accelerationSigma) const {
    // The newest sample at or before t ends the window.
    auto end = std::upper_bound(samples_.begin(), samples_.end(), t,
                                [](double v, const Sample& s) { return v < s.t; });
    if (end == samples_.begin()) return std::nullopt;
    const auto last = std::prev(end);
    if (t - last->t > params_.maxGap) return std::nullopt;
    const double start = last->t - params_.windowSeconds;
    // Backward from the newest: R_i = R(t_i, t_end), the end's frame seen from sample i's.
    Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    std::vector<Eigen::Vector3d> turned;
    double first = last->t;
    for (auto it = last;; --it) {
        if (it != last) {
            const auto next = std::next(it);
            const double dt = next->t - it->t;
            if (dt > params_.maxGap) break;
            const Eigen::Vector3d& w = it->w;  // held from this sample to the next
            if (w.norm() > 0)
                R = Eigen::AngleAxisd(w.norm() * dt, w.normalized()).toRotationMatrix() * R;
        }
        turned.push_back(R.transpose() * it->f);
        sum += turned.back();
        first = it->t;
        if (it == samples_.begin() || std::prev(it)->t < start) break;
    }
    const auto n = static_cast<double>(turned.size());
    // A window covered at least half-way, and enough samples to speak of a spread.
    if (turned.size() < 5 || last->t - first < 0.5 * params_.windowSeconds) return std::nullopt;
    const Eigen::Vector3d mean = sum / n;
    const Eigen::Vector3d reaction = mean - meanAcceleration;  // gravity's, up
    const double g = reaction.norm();
    if (!(g > 0.8 * kGravity && g < 1.2 * kGravity)) return std::nullopt;
    double scatter = 0;
    for (const auto& f : turned) scatter += (f - mean).squaredNorm();
    scatter /= 3 * (n - 1);
    const double independent = std::clamp((last->t - first) / params_.motionSeconds, 1.0, n);
    Up u;
    u.up = reaction / g;
    u.sigma = std::sqrt(params_.biasStd * params_.biasStd + scatter / independent +
                        accelerationSigma * accelerationSigma) /
              g;
    u.samples = static_cast<int>(turned.size());
    return u;
}

void GravityEstimator::dropBefore(double t) {
    const double keep = t - params_.windowSeconds;
    while (samples_.size() >= 2 && samples_[1].t <= keep) samples_.pop_front();
}

}  // namespace lodestone::odometry
