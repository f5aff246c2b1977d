#include "RunParts.h"

#include <lodestone/config/IniSection.h>
#include <lodestone/obs/registerAllClasses.h>
#include <lodestone/slamapp/SlamRun.h>
#include <mrpt/config/CConfigFile.h>

#include <filesystem>

namespace lodestone::slamapp {

void checkSlamConfig(const std::string& configPath) {
    if (!std::filesystem::exists(configPath)) {
        throw detail::InputError("cannot open configuration file '" + configPath + "'");
    }
    const mrpt::config::CConfigFile ini(configPath);
    config::checkSections(ini, detail::allowedSections(), configPath);
    graphslam::SlamEngine::fromConfig(ini);
}

void checkSlamConfig(const std::string& configPath, const std::string& mapIn) {
    checkSlamConfig(configPath);
    if (mapIn.empty()) return;
    SlamRunOptions o;
    o.config = configPath;
    o.mapIn = mapIn;
    const mrpt::config::CConfigFile ini(configPath);
    (void)detail::loadMap(o, detail::configText(o), *graphslam::SlamEngine::fromConfig(ini));
}

SlamRunResult runSlam(const SlamRunOptions& options, std::ostream& out, std::ostream& err) {
    SlamRunResult result;
    lodestone::registerAllClasses();
    // Sources: everything that can be wrong with the inputs, before any work.
    detail::RunInputs inputs;
    try {
        inputs = detail::openInputs(options);
    } catch (const std::exception& e) {
        err << "lodestone-slam: error: " << e.what() << "\n";
        result.exitCode = 1;
        result.error = e.what();
        return result;
    }
    // The loop: a fault in the data stops it; what was processed is still written.
    const auto loop = detail::runLoop(inputs, options, err, result);
    // Outputs.
    try {
        detail::writeOutputs(inputs, loop, options, out, err, result);
    } catch (const std::exception& e) {
        err << "lodestone-slam: error writing outputs: " << e.what() << "\n";
        result.exitCode = 1;
        if (result.error.empty()) result.error = e.what();
    }
    return result;
}

}  // namespace lodestone::slamapp
