#include <lodestone/config/IniSection.h>
#include <lodestone/grab/GrabConfig.h>

#include <filesystem>

namespace lodestone::grab {

GrabConfig readGrabConfig(const std::string& path) {
    if (!std::filesystem::is_regular_file(path)) {
        throw config::ConfigError(path + ": no such grab INI");
    }
    GrabConfig c;
    c.path = path;
    c.ini = std::make_shared<mrpt::config::CConfigFile>(path);
    std::vector<std::string> sections;
    c.ini->getAllSections(sections);
    for (const auto& name : sections) {
        if (name == "global") continue;
        if (!c.ini->keyExists(name, "driver")) continue;
        config::IniSection s(*c.ini, name, path);
        SensorSection sensor;
        sensor.section = name;
        sensor.driver = s.requireString("driver");
        if (sensor.driver.empty()) s.fail("driver", "empty: name a CGenericSensor class");
        sensor.processRate = s.getDouble("process_rate", 50.0);
        if (!(sensor.processRate > 0 && sensor.processRate <= 10000)) {
            s.fail("process_rate", "must be in (0, 10000] Hz");
        }
        c.sensors.push_back(sensor);  // the driver checks the rest of the section
    }
    config::IniSection g(*c.ini, "global", path);
    c.rawlogPrefix = g.getString("rawlog_prefix", "");
    c.gzipLevel = g.getInt("rawlog_GZ_compress_level", 1);
    if (c.gzipLevel < 1 || c.gzipLevel > 9) g.fail("rawlog_GZ_compress_level", "must be 1..9");
    c.reorderWindow = g.getDouble("reorder_window", -1.0);  // unset: from the sensors' rates
    if (g.has("reorder_window") && !(c.reorderWindow >= 0 && c.reorderWindow <= 0.9)) {
        // The window is what a killed grab loses at most, and the bound is 1 s.
        g.fail("reorder_window", "must be in [0, 0.9] s");
    }
    c.statusPeriod = g.getDouble("status_period", 1.0);
    if (!(c.statusPeriod > 0)) g.fail("status_period", "must be > 0 s");
    for (const char* ignored : {"time_between_launches", "use_sensoryframes", "GRABBER_PERIOD_MS"}) {
        g.getString(ignored, "");  // rawlog-grabber's; no meaning here
    }
    g.finish();
    if (c.sensors.empty()) {
        throw config::ConfigError(path + ": no sensor section (a section with 'driver = <class>')");
    }
    return c;
}

}  // namespace lodestone::grab
