#include <lodestone/graphslam/relocalization/ClosureSpace.h>
#include <mrpt/math/wrap2pi.h>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>

namespace lodestone::graphslam::relocalization {

namespace {
// MRPT orders a pose's covariance x, y, z, yaw, pitch, roll.
constexpr int kPlanarFromMrpt[3] = {0, 1, 3};
constexpr int kSpatialFromMrpt[6] = {0, 1, 2, 5, 4, 3};

template <int N>
Eigen::Matrix<double, N, N> covarianceFromInformation(const Constraint& c, const int (&index)[N]) {
    Eigen::Matrix<double, N, N> I;
    for (int r = 0; r < N; ++r)
        for (int k = 0; k < N; ++k) I(r, k) = c.cov_inv(index[r], index[k]);
    return I.ldlt().solve(Eigen::Matrix<double, N, N>::Identity());
}
}  // namespace

PlanarSpace::Pose PlanarSpace::fromGraph(const mrpt::poses::CPose3D& p) {
    return Pose(p.x(), p.y(), p.yaw());
}

mrpt::poses::CPose3D PlanarSpace::toGraph(const Pose& p) {
    return mrpt::poses::CPose3D(p.x(), p.y(), 0, p.phi(), 0, 0);
}

PlanarSpace::Vector PlanarSpace::coordinates(const Pose& p) {
    return Vector(p.x(), p.y(), mrpt::math::wrapToPi(p.phi()));
}

PlanarSpace::Pose PlanarSpace::pose(const Vector& v) { return Pose(v[0], v[1], v[2]); }

PlanarSpace::Vector PlanarSpace::wrapped(Vector d) {
    d[2] = mrpt::math::wrapToPi(d[2]);
    return d;
}

PlanarSpace::Pose PlanarSpace::inverse(const Pose& p) {
    Pose q = p;
    q.inverse();
    return q;
}

PlanarSpace::Matrix PlanarSpace::covarianceOf(const Constraint& c) {
    return covarianceFromInformation<3>(c, kPlanarFromMrpt);
}

SpatialSpace::Vector SpatialSpace::coordinates(const Pose& p) {
    const Eigen::AngleAxisd r(p.getRotationMatrix().asEigen());
    Vector v;
    v << p.x(), p.y(), p.z(), r.angle() * r.axis();
    return v;
}

SpatialSpace::Pose SpatialSpace::pose(const Vector& v) {
    const Eigen::Vector3d w = v.tail<3>();
    const double angle = w.norm();
    const Eigen::Matrix3d R = angle > 0 ? Eigen::AngleAxisd(angle, w / angle).toRotationMatrix()
                                        : Eigen::Matrix3d::Identity();
    mrpt::math::CVectorFixedDouble<3> t;
    for (int k = 0; k < 3; ++k) t[k] = v[k];
    return Pose(mrpt::math::CMatrixDouble33(R), t);
}

SpatialSpace::Pose SpatialSpace::inverse(const Pose& p) { return -p; }

SpatialSpace::Matrix SpatialSpace::covarianceOf(const Constraint& c) {
    return covarianceFromInformation<6>(c, kSpatialFromMrpt);
}

}  // namespace lodestone::graphslam::relocalization
