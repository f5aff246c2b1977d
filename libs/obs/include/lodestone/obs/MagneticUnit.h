#pragma once

#include <optional>
#include <string>
#include <vector>

namespace lodestone::obs {

/** How a raw magnetometer number converts to microtesla: value_uT = raw * microteslaPerUnit.
 *
 * MRPT documents CObservationIMU's IMU_MAG_X/Y/Z in gauss; Xsens drivers (CIMUXSens_MT4)
 * actually fill them with Xsens' normalized units, where 1.0 is the local field strength the
 * device was calibrated in - as do other IMUs calibrated to the unit sphere. No path that brings
 * a magnetometer in assumes one: its unit is said (an option, an INI key, a dataset's
 * documentation) and the readings are checked against Earth's field
 * (implausibleFieldMagnitude) before any work. */
struct MagneticUnit {
    double microteslaPerUnit{1.0};  ///< [uT per raw unit]
    std::string name{"uT"};         ///< as parse() reads it

    static MagneticUnit gauss() { return {100.0, "gauss"}; }
    static MagneticUnit microtesla() { return {1.0, "uT"}; }
    static MagneticUnit tesla() { return {1e6, "T"}; }
    /** Normalized units (1.0: the field at calibration); `localField_uT` is that field's
     * strength [uT]. */
    static MagneticUnit normalized(double localField_uT);
    /** The same, as Xsens names it. */
    static MagneticUnit xsensNormalized(double localField_uT) { return normalized(localField_uT); }

    /** Parses "gauss", "uT", "T", "normalized:<field strength in uT>" (or "xsens:<uT>"); throws
     * std::invalid_argument naming the text otherwise. */
    static MagneticUnit parse(const std::string& text);
};

/** The units an option or INI key takes, for help texts and error messages. */
inline constexpr const char* kMagneticUnitChoices = "gauss|uT|T|normalized:<field strength in uT>";

/** The range of a recording's median field magnitude that is taken for microtesla: Earth's field
 * is 20-70 uT outside steel structures; indoors a building shifts it, seldom by half. Readings in
 * gauss (0.2-0.7), normalized units (about 1), tesla or nanotesla lie a decade or more outside. */
inline constexpr double kPlausibleFieldMin_uT = 10.0;
inline constexpr double kPlausibleFieldMax_uT = 150.0;

/** Why the field magnitudes `magnitudes_uT` (already converted to microtesla; NaN and inf are
 * left out) cannot be Earth's field in microtesla - their median outside
 * [kPlausibleFieldMin_uT, kPlausibleFieldMax_uT], with what unit would fit - or nothing when
 * they can (or no finite reading is given). */
std::optional<std::string> implausibleFieldMagnitude(std::vector<double> magnitudes_uT);

}  // namespace lodestone::obs
