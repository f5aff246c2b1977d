// The simulated magnetic field as the robot meets it: |B| along each scenario's path at the
// first magnetometer's height, sampled every 2 cm. Prints a markdown table row: range and
// spread of |B|, the largest anomaly (deviation from the earth field) and the correlation
// length (the lag at which the autocorrelation of |B| falls to 1/e) - i.e. how strong the
// anomalies are and over what distance they vary.
//   bench_sim_field SCENARIO.ini
#include <lodestone/sim/SimulatorSource.h>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <numeric>

using namespace lodestone::sim;

int main(int argc, char** argv) {
    if (argc != 2) {
        std::cerr << "usage: bench_sim_field SCENARIO.ini\n";
        return 2;
    }
    try {
        Scenario sc = Scenario::load(argv[1]);
        sc.camera.enabled = false;
        SimulatorSource source(sc, sc.seed);
        const auto& mount = sc.magnetometers.at(0).pose;
        const double earth = source.world().field().earthField().norm();
        // One lap's worth of path, resampled by distance.
        std::vector<double> b;
        double travelled = 0, lastX = source.truePose(0).x, lastY = source.truePose(0).y, next = 0;
        for (double t = 0; t < source.duration(); t += 0.005) {
            const RobotPose p = source.truePose(t);
            travelled += std::hypot(p.x - lastX, p.y - lastY);
            lastX = p.x;
            lastY = p.y;
            if (travelled >= next) {
                const auto s = sensorInWorld(p, mount.x, mount.y, mount.z, mount.yaw);
                b.push_back(source.world().field().at(s.position).norm());
                next += 0.02;
            }
        }
        const double mean = std::accumulate(b.begin(), b.end(), 0.0) / b.size();
        double var = 0, lo = 1e9, hi = -1e9, worst = 0;
        for (double v : b) {
            var += (v - mean) * (v - mean);
            lo = std::min(lo, v);
            hi = std::max(hi, v);
            worst = std::max(worst, std::abs(v - earth));
        }
        var /= b.size();
        double corrLength = 0;
        for (std::size_t lag = 1; lag < b.size() / 2; ++lag) {
            double c = 0;
            for (std::size_t i = 0; i + lag < b.size(); ++i)
                c += (b[i] - mean) * (b[i + lag] - mean);
            c /= (b.size() - lag) * var;
            if (c < std::exp(-1.0)) {
                corrLength = lag * 0.02;
                break;
            }
        }
        std::printf("| %s | %.0f | %.1f | %.1f .. %.1f | %.1f | %.1f | %.2f |\n", sc.name.c_str(),
                    travelled, earth, lo, hi, std::sqrt(var), worst, corrLength);
    } catch (const std::exception& e) {
        std::cerr << "bench_sim_field: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
