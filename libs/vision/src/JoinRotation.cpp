#include <lodestone/vision/JoinRotation.h>
#include <lodestone/vision/So3.h>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>

namespace lodestone::vision {

MotionPrior joinRotation(const MotionPrior& camera, const Eigen::Matrix3d& R, double sigma,
                         const Eigen::Vector3d& freeAxis) {
    using Matrix6d = Eigen::Matrix<double, 6, 6>;
    // The measured axes, as rows: all three, or the two across `freeAxis`.
    Eigen::MatrixXd A = Eigen::Matrix3d::Identity();
    if (freeAxis.norm() > 0) {
        const Eigen::Vector3d u = freeAxis.normalized();
        const Eigen::Vector3d a = u.unitOrthogonal(), b = u.cross(a);
        A.resize(2, 3);
        A.row(0) = a.transpose();
        A.row(1) = b.transpose();
    }
    const Eigen::Index m = A.rows();
    // z = A log(R R_cam^T): H = [A 0] on xi; innovation covariance A P_rr A^T + s^2.
    const Eigen::VectorXd z = A * logSO3(R * camera.T_ref_cur.linear().transpose());
    const Matrix6d& P = camera.covariance;
    Eigen::MatrixXd H = Eigen::MatrixXd::Zero(m, 6);
    H.leftCols<3>() = A;
    const Eigen::MatrixXd S =
        H * P * H.transpose() + sigma * sigma * Eigen::MatrixXd::Identity(m, m);
    const Eigen::MatrixXd K = S.ldlt().solve(H * P).transpose();  // P H^T S^-1 (6 x m)
    const Eigen::Matrix<double, 6, 1> xi = K * z;
    MotionPrior joined;
    // exp(xi) T as PointToPlaneIcp's left update: the rotation turned, the translation turned
    // and shifted.
    const Eigen::Matrix3d turn = expSO3(xi.head<3>());
    joined.T_ref_cur.linear() = turn * camera.T_ref_cur.linear();
    joined.T_ref_cur.translation() = turn * camera.T_ref_cur.translation() + xi.tail<3>();
    // (I - K H) P (I - K H)^T + K s^2 K^T (Joseph: stays symmetric and positive)
    const Matrix6d IKH = Matrix6d::Identity() - K * H;
    joined.covariance = IKH * P * IKH.transpose() + sigma * sigma * K * K.transpose();
    joined.covariance = 0.5 * (joined.covariance + joined.covariance.transpose());
    return joined;
}

}  // namespace lodestone::vision
