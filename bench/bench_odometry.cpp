// Odometry on a simulated scenario: wheel-only, VO-only and the two fusions, run on the same VO
// pass, against the simulator's ground truth. Prints markdown table rows:
//   1. per method: ATE RMSE [m], RPE per second [m], RPE per metre [%], final drift [m];
//   2. VO: frames tracked / failed / LOST, matched guided by the wheels / guided that fell back
//      to brute force, RPE per metre over stretches VO tracked throughout,
//      and time per frame split into decode (observation -> frame), ORB, matching, RANSAC.
//   bench_odometry SCENARIO.ini [WIDTHxHEIGHT@HZ|-] [SECONDS] [ODOMETRY.ini]
#include <lodestone/eval/TrajectoryError.h>
#include <lodestone/odometry/FusedOdometry.h>
#include <lodestone/odometry/RgbdObservationFrame.h>
#include <lodestone/sim/RgbdRenderer.h>
#include <lodestone/sim/SimulatorSource.h>
#include <mrpt/config/CConfigFile.h>
#include <mrpt/obs/CObservation3DRangeScan.h>

#include <chrono>
#include <cstdio>
#include <iostream>

using namespace lodestone;

namespace {
/** VO's error over each 1 m of travel whose frames all tracked (and, into `texturedErrs`,
 * whose frames all looked at textured walls too). */
void trackedMetreErrors(const std::vector<io::TumPose>& vo, const std::vector<io::TumPose>& gt,
                        const std::vector<char>& tracked, const std::vector<char>& texturedView,
                        std::vector<double>& errs, std::vector<double>& texturedErrs) {
    std::vector<double> travelled(gt.size(), 0);
    for (std::size_t k = 1; k < gt.size(); ++k) {
        travelled[k] = travelled[k - 1] + std::hypot(gt[k].pose.x() - gt[k - 1].pose.x(),
                                                     gt[k].pose.y() - gt[k - 1].pose.y());
    }
    std::size_t j = 0;
    for (std::size_t i = 0; i < gt.size(); ++i) {
        j = std::max(j, i);
        while (j < gt.size() && travelled[j] - travelled[i] < 1.0) ++j;
        if (j >= gt.size()) break;
        bool all = true, textured = texturedView[i];
        for (std::size_t k = i + 1; k <= j && all; ++k) {
            all = tracked[k];
            textured = textured && texturedView[k];
        }
        if (!all) continue;
        const auto dE = vo[j].pose - vo[i].pose, dG = gt[j].pose - gt[i].pose;
        errs.push_back(std::hypot(dE.x() - dG.x(), dE.y() - dG.y()));
        if (textured) texturedErrs.push_back(errs.back());
    }
}
}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::cerr
            << "usage: bench_odometry SCENARIO.ini [WIDTHxHEIGHT@HZ|-] [SECONDS] [ODOMETRY.ini]\n";
        return 2;
    }
    try {
        sim::Scenario sc = sim::Scenario::load(argv[1]);
        if (argc > 2 && std::string(argv[2]) != "-") {
            if (!sc.camera.override(argv[2])) throw std::runtime_error("bad camera: expected WxH@HZ");
        }
        const double limit = argc > 3 ? std::atof(argv[3]) : 1e9;
        sim::SimulatorSource source(sc, sc.seed);
        odometry::FusedOdometry::Params params;
        if (argc > 4)
            params.loadFromConfigFile(mrpt::config::CConfigFile(argv[4]), "odometry_fusion");
        params.wheels.wheelBase = sc.motion.wheelBase;
        params.wheels.wheelRadius = sc.motion.wheelRadius;
        params.wheels.ticksPerRev = sc.encoders.ticksPerRev;
        const std::vector<std::string> methods = {"wheel", "visual", "kalman", "covariance"};
        odometry::FusedOdometry odo(params, methods);

        std::vector<std::vector<io::TumPose>> est(methods.size());
        std::vector<io::TumPose> gt;
        std::vector<char> tracked, texturedView;
        // What the camera sees, from the world's ground truth: half the columns or more on
        // textured walls makes a "textured" frame.
        const sim::RgbdRenderer truthRenderer(source.world(), sc.camera, 1);
        std::size_t ok = 0, failed = 0, lost = 0;
        double decodeMs = 0, orbMs = 0, matchMs = 0, ransacMs = 0;
        const auto take = [&](const std::vector<odometry::FusedOdometry::Estimate>& es) {
            for (const auto& e : es) {
                for (std::size_t m = 0; m < methods.size(); ++m) {
                    const auto& p = e.poses[m].mean;
                    est[m].push_back(
                        {e.timestamp, mrpt::poses::CPose3D(p.x(), p.y(), 0, p.phi(), 0, 0)});
                }
                const auto t = source.truePose(e.timestamp - sc.startTime);
                gt.push_back({e.timestamp, mrpt::poses::CPose3D(t.x, t.y, 0, t.yaw, 0, 0)});
                tracked.push_back(e.visual.success);
                const auto& cm = sc.camera.pose;
                const auto cs = sim::sensorInWorld(t, cm.x, cm.y, cm.z, cm.yaw);
                texturedView.push_back(truthRenderer.texturedFraction(cs.position, cs.yaw) >= 0.5);
                ok += e.visual.success;
                lost += e.visual.state == vision::VoState::Lost;
                failed += !e.visual.success && e.visual.state != vision::VoState::Lost;
                orbMs += e.visual.timing.orb;
                matchMs += e.visual.timing.matching;
                ransacMs += e.visual.timing.ransac;
            }
        };
        while (auto obs = source.next()) {
            if (source.lastTime() > limit) break;
            if (auto scan = std::dynamic_pointer_cast<mrpt::obs::CObservation3DRangeScan>(obs)) {
                // Decode: what turning the observation into a frame costs (done again inside).
                const auto t0 = std::chrono::steady_clock::now();
                const auto frame = odometry::frameFromObservation(*scan);
                decodeMs +=
                    std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
                        .count();
            }
            take(odo.process(obs));
        }
        take(odo.flush());
        const double n = static_cast<double>(gt.size());
        for (std::size_t m = 0; m < methods.size(); ++m) {
            const auto ate = eval::absoluteTrajectoryError(est[m], gt);
            const auto rpeS = eval::relativePoseError(est[m], gt, eval::RpeInterval::Seconds, 1.0);
            const auto rpeM = eval::relativePoseError(est[m], gt, eval::RpeInterval::Metres, 1.0);
            // Drift: the last pose, both trajectories anchored at their first pose.
            const auto& e0 = est[m].front().pose;
            const auto& g0 = gt.front().pose;
            const auto eEnd = est[m].back().pose - e0, gEnd = gt.back().pose - g0;
            const double drift = std::hypot(eEnd.x() - gEnd.x(), eEnd.y() - gEnd.y());
            std::printf("| %s | %s | %.3f | %.4f | %.2f | %.3f |\n", sc.name.c_str(),
                        methods[m].c_str(), ate.rmse, rpeS.translationRmse,
                        100 * rpeM.translationRmse, drift);
        }
        // VO alone where it tracked: RPE per metre over 1 m pairs with every frame between tracked
        // (and, second figure, every frame between also looking at textured walls).
        std::vector<double> errs, texturedErrs;
        trackedMetreErrors(est[1], gt, tracked, texturedView, errs, texturedErrs);
        const auto rmsOf = [](const std::vector<double>& v) {
            double sq = 0;
            for (double e : v) sq += e * e;
            return v.empty() ? std::nan("") : std::sqrt(sq / v.size());
        };
        const double voRpe = rmsOf(errs), texturedRpe = rmsOf(texturedErrs);
        std::fprintf(stderr,
                     "VO | %s | %dx%d@%.0f | %zu | %zu | %zu | %zu / %zu | %.2f %% (%zu pairs) | "
                     "%.2f %% (%zu pairs) | %.2f | %.2f | %.2f | %.2f | %.2f |\n",
                     sc.name.c_str(), sc.camera.width, sc.camera.height, sc.camera.rate, ok, failed,
                     lost, odo.visual().totals().guided, odo.visual().totals().guidedFallback,
                     100 * voRpe, errs.size(), 100 * texturedRpe, texturedErrs.size(),
                     decodeMs / n, orbMs / n, matchMs / n, ransacMs / n,
                     (decodeMs + orbMs + matchMs + ransacMs) / n);
    } catch (const std::exception& e) {
        std::cerr << "bench_odometry: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
