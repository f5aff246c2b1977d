#include <lodestone/vision/Se3Covariance.h>

namespace lodestone::vision {

Eigen::Matrix<double, 6, 6> adjoint(const Eigen::Isometry3d& A) {
    const Eigen::Matrix3d R = A.linear();
    const Eigen::Vector3d t = A.translation();
    Eigen::Matrix3d tx;
    tx << 0, -t.z(), t.y(), t.z(), 0, -t.x(), -t.y(), t.x(), 0;
    Eigen::Matrix<double, 6, 6> Ad = Eigen::Matrix<double, 6, 6>::Zero();
    Ad.block<3, 3>(0, 0) = R;
    Ad.block<3, 3>(3, 0) = tx * R;
    Ad.block<3, 3>(3, 3) = R;
    return Ad;
}

Eigen::Matrix<double, 6, 6> leftToRightCovariance(const Eigen::Isometry3d& T,
                                                  const Eigen::Matrix<double, 6, 6>& left) {
    const Eigen::Matrix<double, 6, 6> Ad = adjoint(T.inverse());
    return Ad * left * Ad.transpose();
}

}  // namespace lodestone::vision
