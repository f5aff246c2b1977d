// Visual odometry step by step against the truth, read from a rawlog on disk: every frame VO
// gives a motion for is compared with the true motion since its reference frame, grouped by
// how the motion was found - ORB features, or depth alignment where the features failed (by the
// number of directions the depth pinned). For depth-aligned frames the error is split along the
// directions the covariance says were pinned (with their NEES per direction: 1 when the
// covariance is honest) and the rest (the initial guess: the prior or constant velocity).
// The length error: each step's estimate along its true direction, summed, against the true
// lengths summed (with its standard error), as a bias in VO's steps hides in RMS errors.
// The keyframe chain: the same over the steps that became references - the ones VO's motion is
// chained through; a step chosen for its own length error shows here and not in the groups.
// Prints a markdown table row per group; every failed frame is counted by why. With STEPS.csv,
// every tracked frame's step is written there too (a corridor's steps, summed over the
// keyframes - rows whose time is a later row's reference - show a bias the table averages out).
//   bench_depth_alignment RAWLOG GROUND_TRUTH.tum SLAM.ini [NAME [STEPS.csv]]
#include <lodestone/io/RawlogSource.h>
#include <lodestone/io/TumTrajectory.h>
#include <lodestone/obs/registerAllClasses.h>
#include <lodestone/odometry/RgbdObservationFrame.h>
#include <lodestone/vision/RgbdVisualOdometry.h>
#include <mrpt/config/CConfigFile.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/system/datetime.h>

#include <Eigen/Eigenvalues>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <stdexcept>
#include <iostream>
#include <algorithm>
#include <map>
#include <set>

using namespace lodestone;

namespace {
struct Group {
    std::size_t frames{0};
    double sumT2{0}, sumR2{0};              // whole error: translation [m^2], rotation [rad^2]
    double pinnedT2{0}, looseT2{0};         // translation error along pinned / loose directions
    std::size_t pinnedDims{0}, looseDims{0};
    double nees{0};                         // summed over pinned directions
    std::vector<double> translationErrors;  // [m], for the median
    // Length: the estimate along the true direction against the true length, summed over the
    // steps that moved (>= 5 mm): a VO that measures every step short shows here, where RMS
    // errors hide it.
    double trueLength{0}, estAlong{0}, lengthDiff2{0};
};

double median(std::vector<double> v) {
    if (v.empty()) return 0;
    std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
    return v[v.size() / 2];
}

Eigen::Isometry3d toIsometry(const mrpt::poses::CPose3D& p) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.matrix() = p.getHomogeneousMatrixVal<mrpt::math::CMatrixDouble44>().asEigen();
    return T;
}

/** The error split along the covariance's eigen-directions: pinned (under 10 cm: their NEES
 * too) and loose (the initial guess's). */
void addPinnedAndLoose(Group& gr, const Eigen::Matrix<double, 6, 1>& e,
                       const Eigen::Matrix<double, 6, 6>& covariance) {
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>> eig(covariance);
    for (int k = 0; k < 6; ++k) {
        const Eigen::Matrix<double, 6, 1> v = eig.eigenvectors().col(k);
        const double along = v.dot(e);
        const double translationShare = v.tail<3>().squaredNorm();
        if (eig.eigenvalues()(k) < 0.01) {
            gr.nees += along * along / eig.eigenvalues()(k);
            gr.pinnedT2 += translationShare * along * along;
            ++gr.pinnedDims;
        } else {
            gr.looseT2 += translationShare * along * along;
            ++gr.looseDims;
        }
    }
}

/** The table's rows: every frame, each group, the keyframe chain's length, each failure. */
void printRows(const std::string& name, std::size_t frames,
               const std::map<std::string, Group>& groups, const std::set<double>& references,
               const std::map<double, std::pair<double, double>>& stepAt,
               const std::map<std::string, std::size_t>& failed) {
    std::printf("| %s | all frames | %zu |  |  |  |  |  |  |\n", name.c_str(), frames);
    for (const auto& [key, g] : groups) {
        const double n = static_cast<double>(g.frames);
        // The length error's standard error: the steps' differences as independent draws
        // (about their zero, not their mean: conservative where the bias is large).
        const double lengthError = g.trueLength > 0 ? g.estAlong / g.trueLength - 1 : NAN;
        const double lengthSe = g.trueLength > 0 ? std::sqrt(g.lengthDiff2) / g.trueLength : NAN;
        std::printf("| %s | %s | %zu | %.1f / %.1f | %.2f | %+.2f +- %.2f | %.1f | %s | %.2f |\n", name.c_str(),
                    key.c_str(), g.frames, 1000 * median(g.translationErrors),
                    1000 * std::sqrt(g.sumT2 / n),
                    std::sqrt(g.sumR2 / n) * 180 / M_PI, 100 * lengthError, 100 * lengthSe,
                    1000 * std::sqrt(g.pinnedT2 / n),
                    g.looseDims > 0 ? std::to_string(static_cast<int>(1000 * std::sqrt(g.looseT2 / n))).c_str() : "-",
                    g.pinnedDims > 0 ? g.nees / static_cast<double>(g.pinnedDims) : 0.0);
    }
    {
        // (a reference that was not a tracked frame - a start - has no step)
        double chainLength = 0, chainAlong = 0, chainDiff2 = 0;
        std::size_t chainSteps = 0;
        for (const double ref : references) {
            const auto it = stepAt.find(ref);
            if (it == stepAt.end()) continue;
            ++chainSteps;
            chainLength += it->second.first;
            chainAlong += it->second.second;
            chainDiff2 += (it->second.second - it->second.first) * (it->second.second - it->second.first);
        }
        if (chainLength > 0) {
            std::printf("| %s | keyframe chain (steps that became references) | %zu |  |  | %+.2f +- %.2f |  |  |  |\n",
                        name.c_str(), chainSteps, 100 * (chainAlong / chainLength - 1),
                        100 * std::sqrt(chainDiff2) / chainLength);
        }
    }
    for (const auto& [why, count] : failed) {
        std::printf("| %s | failed: %s | %zu |  |  |  |  |  |  |\n", name.c_str(), why.c_str(), count);
    }
}
}  // namespace

int main(int argc, char** argv) {
    if (argc < 4) {
        std::cerr << "usage: bench_depth_alignment RAWLOG GROUND_TRUTH.tum SLAM.ini [NAME [STEPS.csv]]\n";
        return 2;
    }
    try {
        registerAllClasses();  // (a rawlog with magnetometers too)
        const std::string name = argc > 4 ? argv[4] : argv[1];
        vision::RgbdVisualOdometry::Params params;
        params.loadFromConfigFile(mrpt::config::CConfigFile(argv[3]), "visual_odometry");
        vision::RgbdVisualOdometry vo(params);
        const auto truth = io::readTumTrajectory(argv[2]);
        io::RawlogSource source(argv[1]);
        std::map<double, Eigen::Isometry3d> opticalAt;  // true optical-frame poses by timestamp
        std::map<std::string, Group> groups;
        std::map<std::string, std::size_t> failed;
        std::size_t frames = 0;
        std::ofstream steps;
        if (argc > 5) {
            steps.open(argv[5]);
            if (!steps) throw std::runtime_error(std::string("cannot write ") + argv[5]);
            // (the optical frame: x right, y down, z along the view; errors estimate - truth)
            steps << "t,reference_t,how,inliers,true_length,estimate_along,error_x,error_y,error_z,"
                     "sigma_x,sigma_y,sigma_z,rotation_error_x_deg,rotation_error_y_deg,"
                     "rotation_error_z_deg,rotation_sigma_x_deg,rotation_sigma_y_deg,"
                     "rotation_sigma_z_deg\n";
            steps << std::fixed << std::setprecision(6);
        }
        std::map<double, std::pair<double, double>> stepAt;  // t -> true length, estimate along
        std::set<double> references;
        while (auto obs = source.next()) {
            auto scan = std::dynamic_pointer_cast<mrpt::obs::CObservation3DRangeScan>(obs);
            if (!scan) continue;
            ++frames;
            const auto frame = odometry::frameFromObservation(*scan);
            const double t = frame.timestamp;
            if (const auto* g = io::poseNearest(truth, t, 0.02)) {
                opticalAt[t] = toIsometry(g->pose) * odometry::opticalFrameOnRobot(scan->sensorPose);
            }
            const auto r = vo.process(frame);
            if (!r.success) {
                ++failed[r.state == vision::VoState::Initializing ? "initializing" : toString(r.failure)];
                continue;
            }
            const auto cur = opticalAt.find(t), ref = opticalAt.find(r.referenceTimestamp);
            if (cur == opticalAt.end() || ref == opticalAt.end()) {
                ++failed["no ground truth"];
                continue;
            }
            const Eigen::Isometry3d T_true = ref->second.inverse() * cur->second;
            // The error as a left perturbation of the truth: T_est = exp(e) T_true.
            const Eigen::Isometry3d E = r.T_ref_cur * T_true.inverse();
            const Eigen::AngleAxisd aa(E.rotation());
            Eigen::Matrix<double, 6, 1> e;
            e << aa.angle() * aa.axis(), E.translation();
            const std::string key =
                r.depthAligned  ? "depth, " + std::to_string(r.depthObserved) + " pinned"
                : r.depthJoined ? "ORB + depth, " + std::to_string(r.depthObserved) + " pinned"
                                : "ORB features";
            Group& gr = groups[key];
            ++gr.frames;
            gr.sumR2 += e.head<3>().squaredNorm();
            gr.sumT2 += e.tail<3>().squaredNorm();
            gr.translationErrors.push_back(e.tail<3>().norm());
            const double length = T_true.translation().norm();
            if (steps.is_open()) {
                const Eigen::Vector3d d = r.T_ref_cur.translation() - T_true.translation();
                const double deg = 180 / M_PI;
                steps << t << ',' << r.referenceTimestamp << ",\"" << key << "\"," << r.inliers << ','
                      << length << ','
                      << (length > 0 ? r.T_ref_cur.translation().dot(T_true.translation()) / length : 0.0);
                for (int k = 0; k < 3; ++k) steps << ',' << d(k);
                for (int k = 3; k < 6; ++k) steps << ',' << std::sqrt(r.covariance(k, k));
                for (int k = 0; k < 3; ++k) steps << ',' << e(k) * deg;
                for (int k = 0; k < 3; ++k) steps << ',' << std::sqrt(r.covariance(k, k)) * deg;
                steps << '\n';
            }
            const double along = length > 0 ? r.T_ref_cur.translation().dot(T_true.translation()) / length : 0.0;
            stepAt[t] = {length, along};
            references.insert(r.referenceTimestamp);
            if (length >= 0.005) {
                gr.trueLength += length;
                gr.estAlong += along;
                gr.lengthDiff2 += (along - length) * (along - length);
            }
            addPinnedAndLoose(gr, e, r.covariance);
        }
        printRows(name, frames, groups, references, stepAt, failed);
        const auto& tot = vo.totals();
        std::fprintf(stderr, "%s: depth tried %zu, aligned %zu, %.2f ms a frame on depth\n",
                     name.c_str(), tot.depthTried, tot.depthAligned,
                     tot.ms.depth / std::max<std::size_t>(1, tot.frames));
    } catch (const std::exception& e) {
        std::cerr << "bench_depth_alignment: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
