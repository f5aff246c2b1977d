#pragma once

#include <lodestone/obs/MagneticUnit.h>

#include <cstddef>
#include <string>

namespace lodestone::inspect {

struct MagnetometerToImuResult {
    std::size_t entries{0};    ///< top-level entries written
    std::size_t converted{0};  ///< magnetometer observations rewritten as CObservationIMU
    std::size_t commented{0};  ///< wheel-drop observations rewritten as CObservationComment
};

/** Copies `inPath` to `outPath` (gzip if it ends in ".gz"), entry by entry and keeping the
 * rawlog's layout, with every CObservationMagnetometer rewritten as a CObservationIMU carrying
 * IMU_MAG_X/Y/Z in `imuUnit`, and every CObservationWheelDrop (no MRPT counterpart) as a
 * CObservationComment saying its state, so that stock MRPT tools (RawLogViewer, rawlog-edit)
 * open it.
 * On corrupt input the entries before the fault are written, then io::RawlogReadError. */
MagnetometerToImuResult magnetometersToImu(const std::string& inPath, const std::string& outPath,
                                           lodestone::obs::MagneticUnit imuUnit);

}  // namespace lodestone::inspect
