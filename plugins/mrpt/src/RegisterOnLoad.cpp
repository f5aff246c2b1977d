// Runs when a stock MRPT tool dlopen()s the plugin: MRPT_INITIALIZER is a constructor function
// of this module. Observation classes for reading rawlogs, drivers for rawlog-grabber. Registering is idempotent in MRPT, so loading the plugin into a process that
// already registered Lodestone's classes (one of our apps) is harmless.
#include <lodestone/drivers/registerDrivers.h>
#include <lodestone/obs/registerAllClasses.h>
#include <mrpt/core/initializer.h>

MRPT_INITIALIZER(lodestone_mrpt_plugin_register) {
    lodestone::registerAllClasses();
    lodestone::drivers::registerDrivers();
}
