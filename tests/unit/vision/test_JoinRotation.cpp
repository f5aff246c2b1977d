// A camera's motion joined with a gyro's rotation: where the camera's turn and its shift trade
// off (features far ahead: a turn about them), the gyro's turn pins the shift too; where the
// camera is the surer, the gyro moves it little.
#include <gtest/gtest.h>
#include <lodestone/vision/JoinRotation.h>
#include <lodestone/vision/So3.h>

#include <Eigen/Geometry>

using lodestone::vision::MotionPrior;
using lodestone::vision::joinRotation;

namespace {
using Vector6d = Eigen::Matrix<double, 6, 1>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;

/** exp(xi) T (rotation turned, translation turned and shifted). */
Eigen::Isometry3d leftMoved(const Vector6d& xi, const Eigen::Isometry3d& T) {
    Eigen::Isometry3d D = Eigen::Isometry3d::Identity();
    D.linear() = lodestone::vision::expSO3(xi.head<3>());
    D.translation() = xi.tail<3>();
    return D * T;
}

Eigen::Isometry3d stepForward() {  // the truth: 0.1 m along the view (optical z), a slight yaw
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::AngleAxisd(0.02, Eigen::Vector3d::UnitY()).toRotationMatrix();
    T.translation() << 0.0, 0.0, 0.1;
    return T;
}
}  // namespace

// Features 4 m ahead and 1.35 m below (a corridor's floor): a pitch about them is nearly free,
// a shift along the view comes with it. The camera's estimate is 0.5 deg off along that free
// direction (4 cm off in translation), and its covariance says so; the gyro's pitch, sure to
// a hundredth of a degree, brings the translation back to a millimetre.
TEST(JoinRotation, TheGyrosTurnPinsTheShiftThatFarFeaturesTradeForIt) {
    const Eigen::Vector3d about(0.0, 1.35, 4.0);
    Vector6d free;
    free << 1.0, 0.0, 0.0, -Eigen::Vector3d::UnitX().cross(about);
    const double freeSigma = 0.5 * M_PI / 180;
    Matrix6d P = Matrix6d::Identity() * 1e-6;  // (1 mm, 1 mrad elsewhere)
    P += freeSigma * freeSigma * free * free.transpose();
    const Eigen::Isometry3d truth = stepForward();
    const MotionPrior camera{leftMoved(freeSigma * free, truth), P};
    ASSERT_GT((camera.T_ref_cur.translation() - truth.translation()).norm(), 0.035);

    const double gyroSigma = 0.01 * M_PI / 180;
    const MotionPrior joined = joinRotation(camera, truth.linear(), gyroSigma);
    EXPECT_LT((joined.T_ref_cur.translation() - truth.translation()).norm(), 0.002);
    EXPECT_LT(lodestone::vision::logSO3(joined.T_ref_cur.linear() * truth.linear().transpose()).norm(),
              3 * gyroSigma);
    // The free direction is pinned now, in rotation and translation alike.
    const Vector6d unit = free.normalized();
    EXPECT_GT(unit.dot(P * unit), 50 * unit.dot(joined.covariance * unit));
    EXPECT_LT(std::sqrt(joined.covariance(0, 0)), 1.5 * gyroSigma);
    EXPECT_LT(std::sqrt(joined.covariance(5, 5)), 0.002);
    EXPECT_LT((joined.covariance - joined.covariance.transpose()).norm(), 1e-15);
}

// A camera sure of its turn (a textured room close by: 0.01 deg) and a gyro a hundred times
// less sure: the join is the camera's, to a hundredth of the gyro's disagreement.
TEST(JoinRotation, ASurerCameraKeepsItsOwnTurn) {
    const Eigen::Isometry3d truth = stepForward();
    Matrix6d P = Matrix6d::Identity() * 1e-6;
    P.topLeftCorner<3, 3>() = std::pow(0.01 * M_PI / 180, 2) * Eigen::Matrix3d::Identity();
    const MotionPrior camera{truth, P};
    const Eigen::Matrix3d gyro =
        Eigen::AngleAxisd(1.0 * M_PI / 180, Eigen::Vector3d::UnitX()).toRotationMatrix() * truth.linear();
    const MotionPrior joined = joinRotation(camera, gyro, 1.0 * M_PI / 180);
    const double moved = lodestone::vision::logSO3(joined.T_ref_cur.linear() * truth.linear().transpose()).norm();
    EXPECT_NEAR(moved, (1.0 * M_PI / 180) * 1e-4, 1e-7);
    EXPECT_LT((joined.T_ref_cur.translation() - truth.translation()).norm(), 1e-6);
    EXPECT_LE(joined.covariance(0, 0), P(0, 0));
}

// With the vertical left free (a gyro's bias adds up about it unbounded), the gyro corrects
// the camera's tilt and leaves its heading as the camera measured it.
TEST(JoinRotation, WithTheVerticalFreeOnlyTheTiltJoins) {
    const Eigen::Isometry3d truth = stepForward();
    const Eigen::Vector3d vertical(0.0, -1.0, 0.0);  // (optical y points down)
    Matrix6d P = Matrix6d::Identity() * 1e-6;
    P.topLeftCorner<3, 3>() = std::pow(0.5 * M_PI / 180, 2) * Eigen::Matrix3d::Identity();
    Vector6d off = Vector6d::Zero();
    off.head<3>() << 0.5 * M_PI / 180, 1.0 * M_PI / 180, 0.0;  // pitch 0.5 deg, heading 1 deg
    const MotionPrior camera{leftMoved(off, truth), P};
    const double gyroSigma = 0.01 * M_PI / 180;
    const MotionPrior joined = joinRotation(camera, truth.linear(), gyroSigma, vertical);
    const Eigen::Vector3d left = lodestone::vision::logSO3(joined.T_ref_cur.linear() * truth.linear().transpose());
    EXPECT_LT(std::abs(left.x()), 0.02 * M_PI / 180);                // the tilt: the gyro's
    EXPECT_NEAR(left.y(), 1.0 * M_PI / 180, 0.01 * M_PI / 180);       // the heading: the camera's
    EXPECT_NEAR(joined.covariance(1, 1), P(1, 1), 1e-12);
    EXPECT_LT(joined.covariance(0, 0), 2 * gyroSigma * gyroSigma);
    // All three joined, the heading is the gyro's too.
    const MotionPrior all = joinRotation(camera, truth.linear(), gyroSigma);
    EXPECT_LT(lodestone::vision::logSO3(all.T_ref_cur.linear() * truth.linear().transpose()).norm(),
              0.03 * M_PI / 180);
}
