#pragma once

#include <string>
#include <vector>

namespace lodestone::plot {

/** Tick positions at 1, 2 or 5 times a power of ten covering [lo, hi], at most `maxTicks` of
 * them (Heckbert's "nice numbers"). lo == hi gives that single value. */
std::vector<double> niceTicks(double lo, double hi, int maxTicks = 6);

/** A tick's label with as many decimals as the tick step needs ("0.25", "10", "-1.5"). */
std::string tickLabel(double value, double step);

}  // namespace lodestone::plot
