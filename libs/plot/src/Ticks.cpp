#include <lodestone/plot/Ticks.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace lodestone::plot {

namespace {
// The smallest of 1, 2, 5 (x 10^k) at least `x`.
double niceStepAtLeast(double x) {
    const double power = std::pow(10.0, std::floor(std::log10(x)));
    for (const double m : {1.0, 2.0, 5.0, 10.0}) {
        if (m * power >= x * (1 - 1e-9)) return m * power;
    }
    return 10 * power;
}
}  // namespace

std::vector<double> niceTicks(double lo, double hi, int maxTicks) {
    if (!std::isfinite(lo) || !std::isfinite(hi)) return {};
    if (lo > hi) std::swap(lo, hi);
    // A range below the values' own precision has one tick (a step of a few ulps would make
    // k * step stand still).
    if (hi - lo <= 1e-12 * std::max({1.0, std::abs(lo), std::abs(hi)})) return {lo};
    maxTicks = std::max(maxTicks, 2);
    const double step = niceStepAtLeast((hi - lo) / (maxTicks - 1));
    std::vector<double> ticks;
    const double first = std::ceil(lo / step - 1e-9);
    for (int i = 0; i <= maxTicks; ++i) {
        const double t = (first + i) * step;
        if (t > hi + step * 1e-9) break;
        ticks.push_back(std::abs(t) < step * 1e-9 ? 0.0 : t);
    }
    return ticks;
}

std::string tickLabel(double value, double step) {
    const int decimals =
        step >= 1 || step <= 0 ? 0 : static_cast<int>(std::ceil(-std::log10(step) - 1e-9));
    char s[48];
    std::snprintf(s, sizeof s, "%.*f", std::clamp(decimals, 0, 9), value);
    return s;
}

}  // namespace lodestone::plot
