// Is depth alignment's covariance honest, and where not, which error does it miss?
// Pairs of frames along a scenario's robot path (the camera level, as the robot's) are rendered
// by the simulator again and again, each time with a different noise draw, and aligned with
// PointToPlaneIcp exactly as VO does (a grid-sampled cloud against the reference's), started
// from the true motion disturbed by about a constant-velocity guess's error. Alone, and joined
// with a simulated feature measurement drawn from its own (honest) covariance. Per case:
//   - NEES per pinned direction (1 when the covariance is honest);
//   - the same for each pair's error averaged over its draws, against covariance / draws: near
//     1 if the error is the noise's; far above 1 where one error repeats every draw (the
//     geometry's, the sampling's: what no independent-noise Hessian can know);
//   - the share of the error's power that repeats.
// Rendered with the depth as the simulated Kinect gives it, without its disparity steps, and
// without any noise, to tell which error the covariance misses; the clouds' points taken from
// single pixels or from their cells' means (DepthSampling::pointsFromCellMean).
//   bench_depth_honesty SCENARIO.ini [PAIRS] [DRAWS] [STEP_SECONDS]
#include <lodestone/sim/RgbdRenderer.h>
#include <lodestone/sim/SimSensor.h>
#include <lodestone/sim/SimulatorSource.h>
#include <lodestone/vision/depth/PointToPlaneIcp.h>

#include <Eigen/Eigenvalues>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

using namespace lodestone;
using Matrix6d = Eigen::Matrix<double, 6, 6>;
using Vector6d = Eigen::Matrix<double, 6, 1>;

namespace {

/** The camera's optical frame (x right, y down, z forward) in the simulator's (x forward, y
 * left, z up). */
Eigen::Isometry3d opticalInCamera() {
    Eigen::Isometry3d C = Eigen::Isometry3d::Identity();
    C.linear() << 0, 0, 1, -1, 0, 0, 0, -1, 0;
    return C;
}

Eigen::Isometry3d cameraPose(const sim::SimulatorSource& source, const sim::CameraSpec& cam, double t) {
    const sim::SensorWorldPose s =
        sim::sensorInWorld(source.truePose(t), cam.pose.x, cam.pose.y, cam.pose.z, cam.pose.yaw);
    Eigen::Isometry3d P = Eigen::Isometry3d::Identity();
    P.linear() = Eigen::AngleAxisd(s.yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    P.translation() = s.position;
    return P;
}

/** log(T T0^-1) as PointToPlaneIcp's left perturbation (rotation, translation). */
Vector6d leftDifference(const Eigen::Isometry3d& T, const Eigen::Isometry3d& T0) {
    const Eigen::Isometry3d D = T * T0.inverse();
    const Eigen::AngleAxisd aa(D.rotation());
    Vector6d d;
    d << aa.angle() * aa.axis(), D.translation();
    return d;
}

Eigen::Isometry3d leftPerturbed(const Vector6d& dx, const Eigen::Isometry3d& T) {
    Eigen::Isometry3d D = Eigen::Isometry3d::Identity();
    const double angle = dx.head<3>().norm();
    if (angle > 0) D.linear() = Eigen::AngleAxisd(angle, dx.head<3>() / angle).toRotationMatrix();
    D.translation() = dx.tail<3>();
    return D * T;
}

vision::RgbdFrame frameOf(const cv::Mat_<uint16_t>& depthMm, const sim::CameraSpec& cam) {
    vision::RgbdFrame f;
    f.depth = vision::depthToMetres(depthMm, 0.001);
    f.intrinsics = {cam.fx, cam.fy, cam.cx, cam.cy, cam.width, cam.height};
    return f;
}

/** Error along the covariance's pinned eigen-directions (variance under 0.01), squared over
 * the variance: summed, and how many. */
struct Nees {
    double sum{0};
    int dims{0};
    void add(const Vector6d& e, const Matrix6d& covariance) {
        const Eigen::SelfAdjointEigenSolver<Matrix6d> eig(covariance);
        for (int k = 0; k < 6; ++k) {
            if (eig.eigenvalues()(k) >= 0.01) continue;
            const double along = eig.eigenvectors().col(k).dot(e);
            sum += along * along / eig.eigenvalues()(k);
            ++dims;
        }
    }
    double perDim() const { return dims > 0 ? sum / dims : NAN; }
};

struct Case {
    std::string name;
    double depthNoise, disparityStep;
    bool pointsFromCellMean;
};

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::cerr << "usage: bench_depth_honesty SCENARIO.ini [PAIRS] [DRAWS] [STEP_SECONDS]\n";
        return 2;
    }
    try {
        const sim::Scenario base = sim::Scenario::load(argv[1]);
        const int pairs = argc > 2 ? std::atoi(argv[2]) : 60;
        const int draws = argc > 3 ? std::atoi(argv[3]) : 8;
        const double step = argc > 4 ? std::atof(argv[4]) : 0.5;
        if (pairs < 1 || draws < 2 || !(step > 0)) {
            std::cerr << "bench_depth_honesty: PAIRS >= 1, DRAWS >= 2, STEP_SECONDS > 0\n";
            return 2;
        }
        const sim::SimulatorSource source(base, base.seed);
        const Eigen::Isometry3d C = opticalInCamera();
        const vision::PointToPlaneIcp icp;
        // The features' motion as VO measures it at a keyframe step: about 6 mm, 0.1 deg.
        Matrix6d featureCov = Matrix6d::Zero();
        featureCov.topLeftCorner<3, 3>().diagonal().setConstant(std::pow(0.1 * M_PI / 180, 2));
        featureCov.bottomRightCorner<3, 3>().diagonal().setConstant(0.006 * 0.006);
        const Eigen::LLT<Matrix6d> featureChol(featureCov);
        std::printf("| depth rendered | solve | aligned / runs | NEES per pinned direction | "
                    "NEES of each pair's mean error (x draws) | error power that repeats | "
                    "translation error RMS [mm] | rotation error RMS [deg] | worst pair: NEES per direction, at |\n|---|---|---|---|---|---|---|---|---|\n");
        const double noise = base.camera.depthNoise, steps = base.camera.disparityStep;
        const std::vector<Case> cases = {
            {"Kinect (noise + disparity steps), points of single pixels (as shipped)", noise, steps, false},
            {"Kinect, points of cell means", noise, steps, true},
            {"noise, no steps, points of single pixels", noise, 0.0, false},
            {"noise, no steps, points of cell means", noise, 0.0, true},
            {"no noise, points of cell means", 0.0, 0.0, true}};
        for (const Case& c : cases) {
            sim::CameraSpec cam = base.camera;
            cam.depthNoise = c.depthNoise;
            cam.disparityStep = c.disparityStep;
            vision::DepthSampling sampling;  // as rgbd_only.ini: 80 columns, the Kinect's law
            sampling.pointsFromCellMean = c.pointsFromCellMean;
            for (const bool joined : {false, true}) {
                Nees all, means;
                double worstNees = 0, worstAt = 0;  // the pair whose draws claim least honestly
                double repeatPower = 0, totalPower = 0, t2 = 0, r2 = 0;
                int aligned = 0, runs = 0;
                for (int p = 0; p < pairs; ++p) {
                    const double t0 = (source.duration() - step) * (p + 0.5) / pairs;
                    const Eigen::Isometry3d Pref = cameraPose(source, cam, t0),
                                            Pcur = cameraPose(source, cam, t0 + step);
                    const Eigen::Isometry3d T_true = C.inverse() * Pref.inverse() * Pcur * C;
                    Nees pair;
                    Vector6d sum = Vector6d::Zero();
                    Matrix6d covSum = Matrix6d::Zero();
                    std::vector<Vector6d> errors;
                    for (int d = 0; d < draws; ++d) {
                        const std::uint64_t seed = 1000003ULL * static_cast<std::uint64_t>(p) + d + 1;
                        const sim::RgbdRenderer renderer(source.world(), cam, seed);
                        sim::Random rng(seed);
                        cv::Mat3b rgb;
                        cv::Mat_<uint16_t> depthRef, depthCur;
                        renderer.render(Pref, rng, rgb, depthRef);
                        renderer.render(Pcur, rng, rgb, depthCur);
                        vision::DepthModel model(1);
                        model.addReference(vision::sampleDepthCloud(frameOf(depthRef, cam), sampling),
                                           Eigen::Isometry3d::Identity());
                        const vision::DepthCloud cloud =
                            vision::sampleDepthCloud(frameOf(depthCur, cam), sampling);
                        // Started about as far off as a constant-velocity guess.
                        Vector6d guess, z;
                        for (int k = 0; k < 6; ++k) guess(k) = rng.normal();
                        guess.head<3>() *= 0.5 * M_PI / 180;
                        guess.tail<3>() *= 0.01;
                        const Eigen::Isometry3d initial = leftPerturbed(guess, T_true);
                        vision::MotionPrior measured;
                        for (int k = 0; k < 6; ++k) z(k) = rng.normal();
                        measured.T_ref_cur = leftPerturbed(featureChol.matrixL() * z, T_true);
                        measured.covariance = featureCov;
                        ++runs;
                        const vision::DepthAlignment a =
                            icp.align(model, cloud, joined ? measured.T_ref_cur : initial,
                                      joined ? &measured : nullptr);
                        if (!a.success) continue;
                        ++aligned;
                        const Vector6d e = leftDifference(a.T_ref_cur, T_true);
                        all.add(e, a.covariance);
                        pair.add(e, a.covariance);
                        errors.push_back(e);
                        sum += e;
                        covSum += a.covariance;
                        t2 += e.tail<3>().squaredNorm();
                        r2 += e.head<3>().squaredNorm();
                    }
                    if (pair.dims > 0 && pair.perDim() > worstNees) {
                        worstNees = pair.perDim();
                        worstAt = t0;
                    }
                    const auto n = static_cast<double>(errors.size());
                    if (errors.size() < 2) continue;
                    const Vector6d mean = sum / n;
                    // The mean of n independent errors has the mean covariance over n.
                    means.add(mean, covSum / (n * n));
                    // Power in each error's own pinned scaling is what NEES weighs; here plainly,
                    // in metres and radians at a metre.
                    for (const auto& e : errors) totalPower += e.squaredNorm();
                    repeatPower += n * mean.squaredNorm();
                }
                std::printf("| %s | %s | %d / %d | %.2f | %.2f | %.0f %% | %.2f | %.3f | %.1f at %.0f s |\n",
                            c.name.c_str(), joined ? "joined with features (6 mm, 0.1 deg)" : "depth alone",
                            aligned, runs, all.perDim(), means.perDim(),
                            totalPower > 0 ? 100 * repeatPower / totalPower : NAN,
                            aligned > 0 ? 1000 * std::sqrt(t2 / aligned) : NAN,
                            aligned > 0 ? std::sqrt(r2 / aligned) * 180 / M_PI : NAN, worstNees, worstAt);
                std::fflush(stdout);
            }
        }
    } catch (const std::exception& e) {
        std::cerr << "bench_depth_honesty: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
