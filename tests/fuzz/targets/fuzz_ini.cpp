// INI files, read strictly: the first byte picks a SLAM configuration (every component's
// section, as lodestone-slam loads it before touching its input) or a simulator scenario
// (lodestone-sim / lodestone-slam --sim).
#include <lodestone/sim/Scenario.h>
#include <lodestone/slamapp/SlamRun.h>

#include <sstream>

#include "../FuzzInput.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace lodestone;
    if (size == 0) return 0;
    const std::string ini = fuzz::writeScratch("input.ini", data + 1, size - 1);
    if ((data[0] & 1) == 0) {
        // The configuration is checked in full before the rawlog is opened: a rawlog that
        // does not exist ends the run there, with nothing written.
        slamapp::SlamRunOptions options;
        options.config = ini;
        options.rawlog = fuzz::scratchDir() + "/no-such.rawlog";
        options.outDir = fuzz::scratchDir() + "/out";
        options.quiet = true;
        std::ostringstream out, err;
        slamapp::runSlam(options, out, err);
    } else {
        try {
            sim::Scenario::load(ini);
        } catch (const std::exception&) {
        }
    }
    return 0;
}
