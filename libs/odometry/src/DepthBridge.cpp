#include <lodestone/odometry/DepthBridge.h>
#include <lodestone/vision/So3.h>

#include <Eigen/Cholesky>

#include <algorithm>
#include <cstddef>
#include <cmath>
#include <vector>

namespace lodestone::odometry {

namespace {
using vision::skew;

/** The sigma an alignment reports where the depth pins nothing: so loose that a hundred such
 * frames in a gap add no information there (the prediction's guess, not a measurement). */
constexpr double kUnpinnedSigma = 100.0;
/** One depth point's sigma at the cloud's median range: the median of its points' own sigmas
 * (DepthSampling's law, rising with range). */
double depthSigmaOf(const vision::DepthCloud& cloud, double fallback) {
    if (cloud.sigma.size() == 0) return fallback;
    std::vector<float> sigma(cloud.sigma.data(), cloud.sigma.data() + cloud.sigma.size());
    std::nth_element(sigma.begin(), sigma.begin() + static_cast<std::ptrdiff_t>(sigma.size() / 2),
                     sigma.end());
    return sigma[sigma.size() / 2];
}
/** The RMS distance of a cloud's points from their centroid [m] (at least a centimetre). */
double spreadOf(const vision::DepthCloud& cloud) {
    if (cloud.points.cols() == 0) return 1.0;
    const Eigen::MatrixXd p = cloud.points.cast<double>();
    const Eigen::Vector3d c = p.rowwise().mean();
    return std::max(0.01, std::sqrt((p.colwise() - c).squaredNorm() / static_cast<double>(p.cols())));
}
}  // namespace

DepthBridge::DepthBridge(const Params& params) : params_(params) {
    // Every direction the depth pins counts (a plain wall: its distance and two tilts); where it
    // pins none the alignment keeps the prediction, which is then no measurement.
    params_.icp.minObserved = 1;
    params_.icp.unobservedSigma = kUnpinnedSigma;
    turn_ = DepthTurn(params_.turn);
}

void DepthBridge::start(double t0, const vision::RgbdFrame& lastTracked,
                        const Eigen::Isometry3d& T_robot_optical, const Eigen::Vector3d& v0,
                        const Eigen::Matrix3d& v0Covariance, const Eigen::Vector3d& up,
                        const CruiseVelocity& cruise) {
    active_ = true;
    up_ = up.normalized();
    cruise_ = cruise;
    R_predicted_.setIdentity();
    t0_ = t_ = t0;
    aligned_ = rejected_ = cruising_ = beyond_cruise_ = 0;
    x_.setZero();
    x_.segment<3>(3) = v0;
    P_.setZero();
    P_.block<3, 3>(3, 3) = v0Covariance;
    turning_ = false;
    model_.clear();
    anchor(vision::sampleDepthCloud(lastTracked, params_.sampling), T_robot_optical,
           Eigen::Matrix3d::Identity());
}

void DepthBridge::startTurn(const Eigen::Vector3d& w0, const Eigen::Matrix3d& w0Covariance) {
    turning_ = true;
    turn_.start(t0_, w0, w0Covariance, up_);
}

Eigen::Vector3d DepthBridge::displacement() const {
    const Eigen::Vector3d d = x_.head<3>();
    if (!(params_.heightSigma > 0)) return d;
    // The height's prior as one measurement of up . d = 0, once, on what the filter holds.
    const Eigen::Matrix3d P = P_.topLeftCorner<3, 3>();
    const Eigen::Vector3d Pu = P * up_;
    return d - Pu * (up_.dot(d) / (up_.dot(Pu) + params_.heightSigma * params_.heightSigma));
}

Eigen::Matrix3d DepthBridge::covariance() const {
    const Eigen::Matrix3d P = P_.topLeftCorner<3, 3>();
    if (!(params_.heightSigma > 0)) return P;
    const Eigen::Vector3d Pu = P * up_;
    return P - Pu * Pu.transpose() / (up_.dot(Pu) + params_.heightSigma * params_.heightSigma);
}

Eigen::Vector3d DepthBridge::velocity() const {
    const Eigen::Vector3d v = x_.segment<3>(3);
    if (!(params_.heightSigma > 0)) return v;
    // (the height's measurement as in displacement(), its gain on the velocity)
    const Eigen::Vector3d Pu = P_.topLeftCorner<3, 3>() * up_, Pvu = P_.block<3, 3>(3, 0) * up_;
    return v - Pvu * (up_.dot(x_.head<3>()) / (up_.dot(Pu) + params_.heightSigma * params_.heightSigma));
}

Eigen::Matrix3d DepthBridge::velocityCovariance() const {
    const Eigen::Matrix3d P = P_.block<3, 3>(3, 3);
    if (!(params_.heightSigma > 0)) return P;
    const Eigen::Vector3d Pu = P_.topLeftCorner<3, 3>() * up_, Pvu = P_.block<3, 3>(3, 0) * up_;
    return P - Pvu * Pvu.transpose() / (up_.dot(Pu) + params_.heightSigma * params_.heightSigma);
}

void DepthBridge::predict(double t, const Eigen::Matrix3d& R_0) {
    const double dt = std::max(0.0, t - t_);
    t_ = std::max(t_, t);
    if (dt == 0) return;
    // The Ornstein-Uhlenbeck velocity and its integral over dt, per axis (FadingVelocity's
    // model; its displacement variance is the sum of these steps) - the carrier's axes now
    // R_0's, where the velocity across its heading fades sooner; towards the cruise at the
    // step's turn rate where there is one (turned with the carrier).
    Matrix9d F, Q;
    params_.motion.matrices(dt, R_0, F, Q);
    x_ = F * x_;
    if (cruise_.seconds() > 0) {
        const double rate = Eigen::AngleAxisd(R_predicted_.transpose() * R_0).angle() / dt;
        if (cruise_.knows(rate)) {
            ++cruising_;
            x_ += params_.motion.cruiseStep(dt, R_0, cruise_.at(rate));
        } else {
            ++beyond_cruise_;
        }
    }
    R_predicted_ = R_0;
    P_ = F * P_ * F.transpose() + Q;
}

bool DepthBridge::align(const vision::DepthCloud& cloud, const Eigen::Isometry3d& T_robot_optical,
                        const Eigen::Matrix3d& R_0, vision::DepthAlignment& d) const {
    if (model_.empty()) return false;
    // The predicted robot motion from the model frame, then as the camera's; the turn about
    // what the depth does not pin stays the prediction's.
    Eigen::Isometry3d robot = Eigen::Isometry3d::Identity();
    robot.linear() = R_0m_.transpose() * R_0;
    robot.translation() = R_0m_.transpose() * (x_.head<3>() - x_.tail<3>());
    const Eigen::Isometry3d initial = T_robot_optical_m_.inverse() * robot * T_robot_optical;
    d = vision::PointToPlaneIcp(params_.icp).align(model_, cloud, initial);
    return d.success;
}

bool DepthBridge::measureTurn(const vision::DepthAlignment& d, const vision::DepthCloud& cloud,
                              const Eigen::Isometry3d& T_robot_optical) {
    // The alignment's rotation is sure where the depth pinned it, but its covariance holds the
    // directions it did not pin at `kUnpinnedSigma` - and a plane's in-plane translations,
    // taken from noisy normals, carry a thousandth of a radian of rotation with them: metres
    // of free translation become degrees of free rotation. The carrier cannot have moved
    // metres since the model frame: the rotation's covariance is the alignment's given the
    // translation the prediction allows (its information added to the alignment's, on the
    // translation of exp(xi) T: t - [t]x w + v to first order).
    using Matrix6d = Eigen::Matrix<double, 6, 6>;
    const Eigen::Matrix3d Cm = T_robot_optical_m_.linear(), Ck = T_robot_optical.linear();
    Eigen::Matrix<double, 3, 9> H = Eigen::Matrix<double, 3, 9>::Zero();
    H.leftCols<3>() = R_0m_.transpose();
    H.rightCols<3>() = -R_0m_.transpose();
    const Eigen::Matrix3d predicted = Cm.transpose() * (H * P_ * H.transpose()) * Cm;
    Eigen::Matrix<double, 3, 6> J;
    J << -skew(d.T_ref_cur.translation()), Eigen::Matrix3d::Identity();
    const Matrix6d information = d.covariance.ldlt().solve(Matrix6d::Identity()) +
                                 J.transpose() * predicted.ldlt().solve(J);
    // And as the translation's (`measure`): no turn surer than one point's depth over the
    // view's spread - the depth steps a surface's points share tilt it as one (without it the
    // turns claimed 0.1-0.3 deg over a corner and were 0.4-6 deg off).
    const double sigma = depthSigmaOf(cloud, params_.sampling.noiseFloor) / spreadOf(cloud);
    const Eigen::Matrix3d rotationCovariance =
        information.ldlt().solve(Matrix6d::Identity()).topLeftCorner<3, 3>() +
        sigma * sigma * Eigen::Matrix3d::Identity();
    // The robot's rotation from the model frame: Cm R Ck^T; the covariance is of a left
    // perturbation in the model's optical frame - in the model robot frame Cm's turn of it,
    // and as a right perturbation of the rotation, turned back by it.
    const Eigen::Matrix3d R = Cm * d.T_ref_cur.linear() * Ck.transpose();
    const Eigen::Matrix3d A = R.transpose() * Cm;
    if (!turn_.update(R, A * rotationCovariance * A.transpose())) return false;
    R_0m_ = turn_.anchorRotation();
    return true;
}

void DepthBridge::measure(const vision::DepthAlignment& d, const vision::DepthCloud& cloud,
                          const Eigen::Isometry3d& T_robot_optical, const Eigen::Matrix3d& R_0,
                          Eigen::Vector3d& z, Eigen::Matrix3d& Z) const {
    const Eigen::Isometry3d& Cm = T_robot_optical_m_;
    const Eigen::Isometry3d& Ck = T_robot_optical;
    // The translation of exp(xi) T is R(w) t + v: to first order t - [t]x w + v.
    const Eigen::Vector3d t = d.T_ref_cur.translation();
    Eigen::Matrix<double, 3, 6> J;
    J << -skew(t), Eigen::Matrix3d::Identity();
    // No alignment is surer than one point's depth at the view's typical range: the Hessian of
    // thousands of points knows their noise, not what they share (the sensor's depth steps,
    // one at each range) - without this floor a few millimetres of it, taken as certain over
    // a frame interval, are a tenth of a metre per second.
    const double sigma = depthSigmaOf(cloud, params_.sampling.noiseFloor);
    const Eigen::Matrix3d C = J * d.covariance * J.transpose() + sigma * sigma * Eigen::Matrix3d::Identity();
    // Back to the robot: its translation is Cm (optical motion) Ck^-1's, the turn R_0's.
    z = Cm.linear() * t + Cm.translation() - R_0m_.transpose() * R_0 * Ck.translation();
    Z = Cm.linear() * C * Cm.linear().transpose();
}

void DepthBridge::anchor(vision::DepthCloud cloud, const Eigen::Isometry3d& T_robot_optical,
                         const Eigen::Matrix3d& R_0) {
    if (cloud.size() < params_.icp.minCorrespondences) return;  // (the model frame stays)
    model_.clear();
    model_.addReference(std::move(cloud), Eigen::Isometry3d::Identity());
    T_robot_optical_m_ = T_robot_optical;
    R_0m_ = R_0;
    if (turning_) turn_.anchor();
    // The clone: the position here, with every correlation it has.
    x_.tail<3>() = x_.head<3>();
    P_.block<3, 9>(6, 0) = P_.block<3, 9>(0, 0);
    P_.block<9, 3>(0, 6) = P_.block<9, 3>(0, 0);
}

void DepthBridge::add(double t, const vision::RgbdFrame& frame,
                      const Eigen::Isometry3d& T_robot_optical, const Eigen::Matrix3d& R_0) {
    addFrame(t, frame, T_robot_optical, &R_0);
}

void DepthBridge::add(double t, const vision::RgbdFrame& frame,
                      const Eigen::Isometry3d& T_robot_optical) {
    if (turning_) addFrame(t, frame, T_robot_optical, nullptr);
}

void DepthBridge::addFrame(double t, const vision::RgbdFrame& frame,
                           const Eigen::Isometry3d& T_robot_optical, const Eigen::Matrix3d* gyro) {
    if (!active_) return;
    if (!gyro) turn_.predict(t);
    Eigen::Matrix3d R_0 = gyro ? *gyro : turn_.rotation();
    predict(t, R_0);
    vision::DepthCloud cloud = vision::sampleDepthCloud(frame, params_.sampling);
    vision::DepthAlignment d;
    bool measured = align(cloud, T_robot_optical, R_0, d);
    if (measured && !gyro) {
        // The turn first (an alignment it rules out is a wrong minimum: left out whole), then
        // the translation under the turn so measured.
        if (measureTurn(d, cloud, T_robot_optical)) {
            R_0 = turn_.rotation();
        } else {
            ++rejected_;
            measured = false;
        }
    }
    if (measured) {
        Eigen::Vector3d z;
        Eigen::Matrix3d Z;
        measure(d, cloud, T_robot_optical, R_0, z, Z);
        // z = R_0m^T (p - p_m)
        Eigen::Matrix<double, 3, 9> H = Eigen::Matrix<double, 3, 9>::Zero();
        H.leftCols<3>() = R_0m_.transpose();
        H.rightCols<3>() = -R_0m_.transpose();
        const Eigen::Vector3d y = z - H * x_;
        const Eigen::Matrix3d S = H * P_ * H.transpose() + Z;
        const Eigen::LDLT<Eigen::Matrix3d> Sl(S);
        if (y.dot(Sl.solve(y)) > params_.gateChi2) {
            ++rejected_;
        } else {
            const Eigen::Matrix<double, 9, 3> K = Sl.solve(H * P_).transpose();
            x_ += K * y;
            const Matrix9d IKH = Matrix9d::Identity() - K * H;
            P_ = IKH * P_ * IKH.transpose() + K * Z * K.transpose();  // (Joseph: stays symmetric)
            ++aligned_;
        }
    }
    // A new model frame once this one is far enough (as VO's keyframes: fewer, longer steps
    // accumulate less of the depth's quantization), or where it no longer aligned.
    const double moved = (x_.head<3>() - x_.tail<3>()).norm();
    const double turned = Eigen::AngleAxisd(R_0m_.transpose() * R_0).angle();
    if (!measured || moved >= params_.anchorDistance || turned >= params_.anchorAngle)
        anchor(std::move(cloud), T_robot_optical, R_0);
}

}  // namespace lodestone::odometry
