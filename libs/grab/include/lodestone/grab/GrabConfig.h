#pragma once

#include <mrpt/config/CConfigFile.h>

#include <memory>
#include <string>
#include <vector>

namespace lodestone::grab {

/** One sensor of a grab: an INI section with `driver = <CGenericSensor class>`. */
struct SensorSection {
    std::string section;
    std::string driver;
    double processRate{50};  ///< [Hz] doProcess() calls per second (rawlog-grabber's key)
};

/** A grab INI in rawlog-grabber's conventions: `[global]` and a section per sensor with
 * `driver =`; sections without `driver` are left to the drivers (some read others). */
struct GrabConfig {
    std::string path;
    std::shared_ptr<mrpt::config::CConfigFile> ini;  ///< what the drivers read their keys from
    std::vector<SensorSection> sensors;
    // [global]
    std::string rawlogPrefix;     ///< rawlog_prefix: the output, without .rawlog.gz
    int gzipLevel{1};             ///< rawlog_GZ_compress_level (1..9)
    /** reorder_window [s]: how late an observation may arrive; negative (unset): twice the
     * slowest sensor's period, at least 0.05 s. */
    double reorderWindow{-1.0};
    double statusPeriod{1.0};     ///< status_period [s] between status lines
};

/** Reads and checks `path`; throws config::ConfigError (file, section, key) on an unknown
 * [global] key, a bad value, a sensor section without a driver name or a file without
 * sensors. rawlog-grabber's [global] keys that do not apply here (time_between_launches,
 * use_sensoryframes, GRABBER_PERIOD_MS) are accepted and ignored. */
GrabConfig readGrabConfig(const std::string& path);

}  // namespace lodestone::grab
