// Frames rendered per second by the simulator's RGB-D camera, on one core, for each scenario
// and resolution given. Prints one markdown table row per case.
//   bench_sim_render SCENARIO.ini WIDTHxHEIGHT [FRAMES]
#include <lodestone/sim/RgbdRenderer.h>
#include <lodestone/sim/SimulatorSource.h>

#include <chrono>
#include <cstdio>
#include <iostream>

using namespace lodestone::sim;

int main(int argc, char** argv) {
    if (argc < 3) {
        std::cerr << "usage: bench_sim_render SCENARIO.ini WIDTHxHEIGHT [FRAMES]\n";
        return 2;
    }
    try {
        Scenario sc = Scenario::load(argv[1]);
        int w = 0, h = 0;
        if (std::sscanf(argv[2], "%dx%d", &w, &h) != 2 || w < 16 || h < 16) {
            std::cerr << "bad size '" << argv[2] << "'\n";
            return 2;
        }
        sc.camera.resize(w, h);
        const int frames = argc > 3 ? std::atoi(argv[3]) : 200;
        SimulatorSource source(sc, sc.seed);
        RgbdRenderer renderer(source.world(), sc.camera, 1);
        Random rng(1);
        cv::Mat3b rgb;
        cv::Mat_<uint16_t> depth;
        const double duration = source.duration();
        // Poses spread over the whole run, so every kind of wall is seen.
        const auto t0 = std::chrono::steady_clock::now();
        std::size_t valid = 0;
        for (int i = 0; i < frames; ++i) {
            const RobotPose p = source.truePose(duration * i / frames);
            const auto& m = sc.camera.pose;
            const SensorWorldPose s = sensorInWorld(p, m.x, m.y, m.z, m.yaw);
            renderer.render(s.position, s.yaw, rng, rgb, depth);
            valid += static_cast<std::size_t>(cv::countNonZero(depth));
        }
        const double secs =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        std::printf("| %s | %dx%d | %d | %.2f | %.1f | %.0f %% |\n", sc.name.c_str(), w, h, frames,
                    1e3 * secs / frames, frames / secs, 100.0 * valid / (double(frames) * w * h));
    } catch (const std::exception& e) {
        std::cerr << "bench_sim_render: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
