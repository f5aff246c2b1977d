// lodestone-slam's engine on a simulated scenario, against the simulator's ground truth and
// against the fused odometry alone (the odometry issue's estimate, run on the same data).
// Prints one markdown row:
//   scenario | camera | config | nodes | closures | ATE graph [m] | ATE fused odometry at the
//   node times [m] | difference [m] | engine ms per frame mean / p99 | real-time factor of the
//   engine | per-node ms by decile of the run
// The engine time excludes rendering the simulated sensors.
//   bench_slam SCENARIO.ini SLAM.ini [WIDTHxHEIGHT@HZ|-] [SECONDS]
#include <lodestone/eval/TrajectoryError.h>
#include <lodestone/graphslam/nrd/FusedOdometryNRD.h>
#include <lodestone/graphslam/SlamEngine.h>
#include <lodestone/sim/RobotConfig.h>
#include <lodestone/sim/SimulatorSource.h>
#include <mrpt/config/CConfigFile.h>

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <map>

using namespace lodestone;

int main(int argc, char** argv) {
    if (argc < 3) {
        std::cerr << "usage: bench_slam SCENARIO.ini SLAM.ini [WIDTHxHEIGHT@HZ|-] [SECONDS]\n";
        return 2;
    }
    try {
        sim::Scenario sc = sim::Scenario::load(argv[1]);
        if (argc > 3 && std::string(argv[3]) != "-") {
            if (!sc.camera.override(argv[3])) throw std::runtime_error("bad camera: expected WxH@HZ");
        }
        char cam[64];
        std::snprintf(cam, sizeof cam, "%dx%d@%.0f", sc.camera.width, sc.camera.height, sc.camera.rate);
        const double limit = argc > 4 ? std::atof(argv[4]) : 1e9;
        const mrpt::config::CConfigFile ini(argv[2]);
        const auto robotIni = sim::withScenarioWheels(ini, sc, argv[2]);
        auto engine = graphslam::SlamEngine::fromConfig(robotIni);
        // The same odometry as the node decider's, alone beside the engine.
        odometry::FusedOdometry::Params odometryParams;
        odometryParams.loadFromConfigFile(robotIni, "odometry_fusion");
        odometry::FusedOdometry odo(odometryParams);

        sim::SimulatorSource source(sc, sc.seed);
        std::map<double, mrpt::poses::CPose2D> fused;
        double t0 = -1, tEnd = 0;
        while (auto obs = source.next()) {
            if (source.lastTime() > limit) break;
            const double t = mrpt::Clock::toDouble(obs->timestamp);
            if (t0 < 0) t0 = t;
            tEnd = t;
            engine->process(obs);
            for (const auto& e : odo.process(obs)) fused[e.timestamp] = e.poses.front().mean;
        }
        engine->finish();
        for (const auto& e : odo.flush()) fused[e.timestamp] = e.poses.front().mean;

        std::vector<io::TumPose> graph, odometry, truth;
        const auto& nodes = engine->nodes();
        for (graphslam::TNodeID id = 0; id < nodes.size(); ++id) {
            const double t = nodes.at(id).timestamp;
            graph.push_back({t, engine->graph().nodes.at(id)});
            const auto& f = fused.at(t);
            odometry.push_back({t, mrpt::poses::CPose3D(f.x(), f.y(), 0, f.phi(), 0, 0)});
            const auto p = source.truePose(t - sc.startTime);
            truth.push_back({t, mrpt::poses::CPose3D(p.x, p.y, 0, p.yaw, 0, 0)});
        }
        const auto ateGraph = eval::absoluteTrajectoryError(graph, truth);
        const auto ateOdo = eval::absoluteTrajectoryError(odometry, truth);
        const auto& st = engine->stats();
        std::vector<float> frames = st.frameMs;
        std::sort(frames.begin(), frames.end());
        double sum = 0, engineSeconds = 0;
        for (float f : frames) sum += f;
        for (float f : st.nodeMs) engineSeconds += f / 1e3;
        const double p99 = frames.empty() ? 0 : frames[std::min(frames.size() - 1, frames.size() * 99 / 100)];
        std::string deciles;
        for (int d = 0; d < 10 && st.nodeMs.size() >= 10; ++d) {
            const std::size_t a = st.nodeMs.size() * d / 10, b = st.nodeMs.size() * (d + 1) / 10;
            double s = 0;
            for (std::size_t i = a; i < b; ++i) s += st.nodeMs[i];
            char buf[16];
            std::snprintf(buf, sizeof buf, "%s%.0f", d ? " " : "", s / (b - a));
            deciles += buf;
        }
        std::size_t closures = engine->optimizer().loopClosures().size();
        const std::string cfg = std::string(argv[2]).substr(std::string(argv[2]).rfind('/') + 1);
        std::printf("| %s | %s | %s | %zu | %zu | %.3f | %.3f | %.1e | %.1f / %.1f | %.2fx | %s |\n",
                    sc.name.c_str(), cam, cfg.c_str(), nodes.size(), closures, ateGraph.rmse,
                    ateOdo.rmse, std::abs(ateGraph.rmse - ateOdo.rmse),
                    frames.empty() ? 0.0 : sum / frames.size(), p99,
                    engineSeconds > 0 ? (tEnd - t0) / engineSeconds : 0.0, deciles.c_str());
    } catch (const std::exception& e) {
        std::cerr << "bench_slam: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
