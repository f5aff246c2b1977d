#include <lodestone/datasets/SyntheticOdometry.h>

#include <cmath>
#include <random>
#include <stdexcept>

namespace lodestone::datasets {

std::vector<SyntheticOdometrySample> synthesizeOdometry(const MagneticRecording& recording,
                                                        const OdometryDriftModel& model) {
    if (!(model.sp2 >= 0) || !(model.sh2 >= 0)) {
        throw std::invalid_argument("odometry drift model: variances must be >= 0");
    }
    if (!std::isfinite(model.bias))
        throw std::invalid_argument("odometry drift model: bias must be finite");
    if (!(model.rate >= 0)) throw std::invalid_argument("odometry drift model: rate must be >= 0");
    std::vector<SyntheticOdometrySample> out;
    const auto& s = recording.samples;
    if (s.empty()) return out;
    std::mt19937_64 rng(model.seed);
    std::normal_distribution<double> gauss(0.0, 1.0);
    const double sp = std::sqrt(model.sp2), sh = std::sqrt(model.sh2);
    long lastTick = -1;
    std::size_t previous = 0;
    mrpt::poses::CPose2D pose;
    for (std::size_t i = 0; i < s.size(); ++i) {
        if (model.rate > 0) {
            const long tick = std::lround((s[i].t - s[0].t) * model.rate);
            if (tick <= lastTick) continue;
            lastTick = tick;
        }
        if (!out.empty()) {
            // The reference's motion in the body frame of the previous odometry sample.
            const auto& a = s[previous];
            const auto& b = s[i];
            const double c = std::cos(a.heading), sn = std::sin(a.heading);
            const double dx = b.x - a.x, dy = b.y - a.y;
            const double fx = c * dx + sn * dy + sp * gauss(rng);
            const double fy = -sn * dx + c * dy + sp * gauss(rng);
            const double dh = (b.heading - a.heading) + model.bias * (b.t - a.t) + sh * gauss(rng);
            pose = pose + mrpt::poses::CPose2D(fx, fy, dh);
        }
        out.push_back({i, s[i].t, pose});
        previous = i;
    }
    return out;
}

}  // namespace lodestone::datasets
