#include <lodestone/graphslam/Se3Pose.h>
#include <mrpt/math/wrap2pi.h>

#include <Eigen/Cholesky>

namespace lodestone::graphslam {

Eigen::Isometry3d isometryOf(const mrpt::poses::CPose3D& p) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = p.getRotationMatrix().asEigen();
    T.translation() = Eigen::Vector3d(p.x(), p.y(), p.z());
    return T;
}

mrpt::poses::CPose3D poseOf3D(const Eigen::Isometry3d& T) {
    mrpt::math::CMatrixDouble44 M(T.matrix());
    return mrpt::poses::CPose3D(M);
}

mrpt::math::CMatrixDouble66 mrptCovarianceOf(const Eigen::Matrix<double, 6, 6>& cov) {
    constexpr int kFromTwist[6] = {3, 4, 5, 2, 1, 0};  // MRPT index -> twist index
    mrpt::math::CMatrixDouble66 c;
    for (int r = 0; r < 6; ++r)
        for (int k = 0; k < 6; ++k) c(r, k) = cov(kFromTwist[r], kFromTwist[k]);
    return c;
}

double squaredMahalanobis(const mrpt::poses::CPose3DPDFGaussian& a,
                          const mrpt::poses::CPose3DPDFGaussian& b) {
    Eigen::Matrix<double, 6, 1> d;
    for (int k = 0; k < 6; ++k) d[k] = b.mean[k] - a.mean[k];
    for (int k = 3; k < 6; ++k) d[k] = mrpt::math::wrapToPi(d[k]);
    Eigen::Matrix<double, 6, 6> S = a.cov.asEigen() + b.cov.asEigen();
    S.diagonal().array() += 1e-12;  // (two certain poses: any difference is far)
    return d.dot(S.ldlt().solve(d));
}

mrpt::poses::CPose3DPDFGaussian heightHeld(const mrpt::poses::CPose3DPDFGaussian& pdf, double sigma,
                                           bool moveRotation) {
    if (!(sigma > 0)) return pdf;
    const Eigen::Matrix<double, 6, 6> C = pdf.cov.asEigen();  // (x, y, z, yaw, pitch, roll)
    Eigen::Matrix<double, 6, 1> Ch = C.col(2);
    if (!moveRotation) Ch.tail<3>().setZero();
    const Eigen::Matrix<double, 6, 1> K = Ch / (C(2, 2) + sigma * sigma);
    const auto& m = pdf.mean;
    const Eigen::Matrix<double, 6, 1> x =
        (Eigen::Matrix<double, 6, 1>() << m.x(), m.y(), m.z(), m.yaw(), m.pitch(), m.roll()).finished() -
        K * m.z();
    mrpt::poses::CPose3DPDFGaussian held;
    held.mean = mrpt::poses::CPose3D(x(0), x(1), x(2), x(3), x(4), x(5));
    Eigen::Matrix<double, 6, 6> P = C - K * Ch.transpose();
    if (!moveRotation) {  // (the rotation's block as it was, and no cross terms left to it)
        P.topRightCorner<3, 3>().setZero();
        P.bottomLeftCorner<3, 3>().setZero();
        P.bottomRightCorner<3, 3>() = C.bottomRightCorner<3, 3>();
    }
    held.cov = mrpt::math::CMatrixDouble66(P);
    return held;
}

mrpt::poses::CPose3DPDFGaussian translationHeld(const mrpt::poses::CPose3DPDFGaussian& pdf,
                                                const Eigen::Vector3d& m, const Eigen::Matrix3d& M,
                                                bool moveRotation) {
    using Matrix6d = Eigen::Matrix<double, 6, 6>;
    using Vector6d = Eigen::Matrix<double, 6, 1>;
    const Matrix6d C = pdf.cov.asEigen();  // (x, y, z, yaw, pitch, roll)
    Eigen::Matrix<double, 6, 3> Ct = C.leftCols<3>();
    if (!moveRotation) Ct.bottomRows<3>().setZero();
    const Eigen::Matrix3d S = C.topLeftCorner<3, 3>() + M;
    const Eigen::Matrix<double, 6, 3> K = Ct * S.ldlt().solve(Eigen::Matrix3d::Identity());
    const auto& p = pdf.mean;
    const Vector6d x = (Vector6d() << p.x(), p.y(), p.z(), p.yaw(), p.pitch(), p.roll()).finished() +
                       K * (m - Eigen::Vector3d(p.x(), p.y(), p.z()));
    mrpt::poses::CPose3DPDFGaussian held;
    held.mean = mrpt::poses::CPose3D(x(0), x(1), x(2), x(3), x(4), x(5));
    Matrix6d P = C - K * Ct.transpose();
    P = 0.5 * (P + P.transpose());
    if (!moveRotation) {  // (as heightHeld's)
        P.topRightCorner<3, 3>().setZero();
        P.bottomLeftCorner<3, 3>().setZero();
        P.bottomRightCorner<3, 3>() = C.bottomRightCorner<3, 3>();
    }
    held.cov = mrpt::math::CMatrixDouble66(P);
    return held;
}

mrpt::poses::CPose3DPDFGaussianInf closureConstraint(const Eigen::Isometry3d& T,
                                                     const Eigen::Matrix<double, 6, 6>& cov,
                                                     double minSigmaXY, double minSigmaYaw) {
    mrpt::math::CMatrixDouble66 c = mrptCovarianceOf(cov);
    for (int k = 0; k < 3; ++k) c(k, k) += minSigmaXY * minSigmaXY;
    for (int k = 3; k < 6; ++k) c(k, k) += minSigmaYaw * minSigmaYaw;
    mrpt::poses::CPose3DPDFGaussianInf out;
    out.mean = poseOf3D(T);
    out.cov_inv = c.inverse_LLt();
    return out;
}

}  // namespace lodestone::graphslam
