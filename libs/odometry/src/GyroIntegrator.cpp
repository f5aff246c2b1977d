#include <lodestone/odometry/GyroIntegrator.h>
#include <mrpt/system/datetime.h>

#include <cmath>

namespace lodestone::odometry {

bool GyroIntegrator::add(const mrpt::obs::CObservationIMU& imu) {
    using mrpt::obs::IMU_WX, mrpt::obs::IMU_WY, mrpt::obs::IMU_WZ;
    if (!imu.has(IMU_WX) || !imu.has(IMU_WY) || !imu.has(IMU_WZ)) return false;
    const Eigen::Vector3d w(imu.get(IMU_WX), imu.get(IMU_WY), imu.get(IMU_WZ));
    const double t = mrpt::Clock::toDouble(imu.timestamp);
    if (!w.allFinite() || !std::isfinite(t)) return false;
    if (!samples_.empty() && t <= samples_.back().t) return false;
    samples_.push_back({t, w});
    sensor_on_robot_.matrix() = imu.sensorPose.getHomogeneousMatrixVal<mrpt::math::CMatrixDouble44>().asEigen();
    return true;
}

std::optional<GyroIntegrator::Rotation> GyroIntegrator::between(double t0, double t1) const {
    if (samples_.empty() || !(t1 >= t0)) return std::nullopt;
    // Covered: a sample at or before t0, none further apart than maxGap, and the last no more
    // than maxGap before t1 (held to t1: a camera frame often comes between two samples).
    if (samples_.front().t > t0 || samples_.back().t < t1 - params_.maxGap) return std::nullopt;
    Rotation r;
    r.R.setIdentity();
    double noiseVar = 0;
    for (std::size_t i = 0; i < samples_.size(); ++i) {
        const double next = i + 1 < samples_.size() ? samples_[i + 1].t : t1;
        const double a = std::max(samples_[i].t, t0), b = std::min(next, t1);
        if (b <= a) continue;
        if (next - samples_[i].t > params_.maxGap) return std::nullopt;
        // A sample is the rate at its instant: between two, the rate runs linearly from one to
        // the next, and [a, b] turns at its value at the middle (exact for a steady change of
        // rate). Held forward from each sample instead, a turn's rotation lags half a sample:
        // at a gap's end in a 40 deg/s turn, 0.2 deg short and sure of it. After the last
        // sample the rate is held.
        Eigen::Vector3d w = samples_[i].w;
        if (i + 1 < samples_.size()) {
            const double u = (0.5 * (a + b) - samples_[i].t) / (next - samples_[i].t);
            w += u * (samples_[i + 1].w - samples_[i].w);
        }
        w -= bias_;
        const double dt = b - a;
        if (w.norm() > 0) r.R = r.R * Eigen::AngleAxisd(w.norm() * dt, w.normalized()).toRotationMatrix();
        // White rate noise of a sample held for its interval h: variance noise^2 dt h.
        noiseVar += params_.noiseStd * params_.noiseStd * dt * (next - samples_[i].t);
    }
    const double T = t1 - t0;
    r.sigma = std::sqrt(noiseVar + params_.biasStd * params_.biasStd * T * T);
    return r;
}

void GyroIntegrator::setBias(const Eigen::Vector3d& bias, double biasStd) {
    bias_ = bias;
    params_.biasStd = biasStd;
}

void GyroIntegrator::dropBefore(double t) {
    while (samples_.size() >= 2 && samples_[1].t <= t) samples_.pop_front();
}

}  // namespace lodestone::odometry
