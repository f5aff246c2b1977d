#pragma once

#include <string>

namespace lodestone::obs {

/** How a raw magnetometer number converts to microtesla: value_uT = raw * microteslaPerUnit.
 *
 * MRPT documents CObservationIMU's IMU_MAG_X/Y/Z in gauss; Xsens drivers (CIMUXSens_MT4)
 * actually fill them with Xsens' normalized units, where 1.0 is the local field strength the
 * device was calibrated in. */
struct MagneticUnit {
    double microteslaPerUnit{100.0};  ///< [uT per raw unit]; gauss by default

    static MagneticUnit gauss() { return {100.0}; }
    static MagneticUnit microtesla() { return {1.0}; }
    static MagneticUnit tesla() { return {1e6}; }
    /** Xsens normalized units; `localField_uT` is the field strength at calibration [uT]. */
    static MagneticUnit xsensNormalized(double localField_uT) { return {localField_uT}; }

    /** Parses "gauss", "uT", "T" or "xsens:<local field in uT>"; throws std::invalid_argument
     * naming the text otherwise. */
    static MagneticUnit parse(const std::string& text);
};

}  // namespace lodestone::obs
