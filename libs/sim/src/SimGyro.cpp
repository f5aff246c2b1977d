#include <lodestone/sim/SimGyro.h>
#include <mrpt/obs/CObservationIMU.h>

#include <algorithm>

namespace lodestone::sim {

SimGyro::SimGyro(const MotionPlan& plan, const HandheldMotion* handheld, const GyroSpec& spec,
                 double startTime, Random rng)
    : plan_(plan),
      handheld_(handheld),
      spec_(spec),
      start_time_(startTime),
      rng_(rng),
      accel_rng_(rng.fork(0xacce1)),
      clock_(spec.rate) {
    bias_ = spec_.biasSigma * Eigen::Vector3d(rng_.normal(), rng_.normal(), rng_.normal());
    accel_bias_ = spec_.accelBiasSigma *
                  Eigen::Vector3d(accel_rng_.normal(), accel_rng_.normal(), accel_rng_.normal());
}

std::int64_t SimGyro::nextTimeNs() const { return clock_.nextWithin(plan_.duration()); }

Eigen::Vector3d SimGyro::trueRate(double t) const {
    if (!handheld_) {
        // A level gyro on the robot turns with it about z only (its mount's yaw does not change
        // that).
        return {0, 0, plan_.velocityAt(t).y()};
    }
    // The body rate of the camera: the rotation between two instants 1 ms either side.
    const double h = 1e-3;
    const double a = std::max(0.0, t - h), b = std::min(plan_.duration(), t + h);
    if (!(b > a)) return Eigen::Vector3d::Zero();
    const Eigen::Matrix3d Ra = handheld_->poseAt(a).linear(), Rb = handheld_->poseAt(b).linear();
    const Eigen::AngleAxisd d(Ra.transpose() * Rb);
    return d.angle() * d.axis() / (b - a);
}

Eigen::Isometry3d SimGyro::sensorPoseAt(double t) const {
    if (handheld_) return handheld_->poseAt(t);
    const RobotPose p = plan_.poseAt(t);
    const auto& m = spec_.pose;
    Eigen::Isometry3d robot = Eigen::Isometry3d::Identity();
    robot.translation() = Eigen::Vector3d(p.x, p.y, p.z);
    robot.linear() = Eigen::AngleAxisd(p.yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    Eigen::Isometry3d mount = Eigen::Isometry3d::Identity();
    mount.translation() = Eigen::Vector3d(m.x, m.y, m.z);
    mount.linear() = Eigen::AngleAxisd(m.yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    return robot * mount;
}

Eigen::Vector3d SimGyro::trueSpecificForce(double t) const {
    // The sensor's acceleration by central differences 5 ms either side (one-sided at the ends).
    const double h = 5e-3;
    const double a = std::max(0.0, t - h), b = std::min(plan_.duration(), t + h);
    const double m = 0.5 * (a + b);
    Eigen::Vector3d acc = Eigen::Vector3d::Zero();
    if (b > a) {
        const double half = 0.5 * (b - a);
        acc = (sensorPoseAt(b).translation() - 2 * sensorPoseAt(m).translation() +
               sensorPoseAt(a).translation()) /
              (half * half);
    }
    const Eigen::Vector3d gravityUp(0, 0, 9.81);
    return sensorPoseAt(t).linear().transpose() * (acc + gravityUp);
}

mrpt::obs::CObservation::Ptr SimGyro::produce() {
    const std::int64_t tNs = clock_.now();
    ++clock_.k;
    const Eigen::Vector3d w =
        trueRate(tNs * 1e-9) + bias_ +
        spec_.noiseStd * Eigen::Vector3d(rng_.normal(), rng_.normal(), rng_.normal());
    auto obs = mrpt::obs::CObservationIMU::Create();
    obs->timestamp = simTimestamp(start_time_, tNs);
    obs->sensorLabel = spec_.label;
    const auto& m = spec_.pose;
    obs->sensorPose =
        handheld_ ? mrpt::poses::CPose3D() : mrpt::poses::CPose3D(m.x, m.y, m.z, m.yaw, 0, 0);
    obs->set(mrpt::obs::IMU_WX, w.x());
    obs->set(mrpt::obs::IMU_WY, w.y());
    obs->set(mrpt::obs::IMU_WZ, w.z());
    const Eigen::Vector3d f =
        trueSpecificForce(tNs * 1e-9) + accel_bias_ +
        spec_.accelNoiseStd *
            Eigen::Vector3d(accel_rng_.normal(), accel_rng_.normal(), accel_rng_.normal());
    obs->set(mrpt::obs::IMU_X_ACC, f.x());
    obs->set(mrpt::obs::IMU_Y_ACC, f.y());
    obs->set(mrpt::obs::IMU_Z_ACC, f.z());
    return obs;
}

}  // namespace lodestone::sim
