#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace lodestone::vision {

/** [a]x: the matrix of a x (.). */
inline Eigen::Matrix3d skew(const Eigen::Vector3d& a) {
    Eigen::Matrix3d S;
    S << 0, -a.z(), a.y(), a.z(), 0, -a.x(), -a.y(), a.x(), 0;
    return S;
}

/** The rotation of a rotation vector (exp on SO(3)), and back (log). */
inline Eigen::Matrix3d expSO3(const Eigen::Vector3d& w) {
    const double angle = w.norm();
    if (angle < 1e-12) return Eigen::Matrix3d::Identity() + skew(w);
    return Eigen::AngleAxisd(angle, w / angle).toRotationMatrix();
}
inline Eigen::Vector3d logSO3(const Eigen::Matrix3d& R) {
    const Eigen::AngleAxisd aa(R);
    return aa.angle() * aa.axis();
}

}  // namespace lodestone::vision
