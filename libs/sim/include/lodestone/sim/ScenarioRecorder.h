#pragma once

#include <lodestone/sim/SimulatorSource.h>

#include <functional>
#include <string>

namespace lodestone::sim {

/** What a recording wrote. */
struct RecordingSummary {
    std::string rawlog, groundTruth, events, imagesDir;
    std::size_t observations{0}, frames{0};
    double duration{0};  ///< [s] of simulated time
};

/** Runs a scenario to its end and writes `OUT.rawlog` (gzip if it ends in .gz), `OUT.gt.tum`
 * (the true robot pose at every observation's timestamp) and `OUT.events.txt` (kidnaps). RGB-D
 * colour images go to `<OUT>_Images/` as PNG when the scenario asks for external images (MRPT's
 * delay-load convention, which stock tools follow); depth stays in the rawlog. Everything is
 * written streaming. `progress(fraction)` is called now and then. */
RecordingSummary recordScenario(SimulatorSource& source, const std::string& outRawlog,
                                const std::function<void(double)>& progress = {});

}  // namespace lodestone::sim
