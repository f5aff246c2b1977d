#pragma once

#include <cstddef>
#include <string>

namespace lodestone::inspect {

/** What exportSensor wrote. */
struct SensorExportResult {
    std::size_t seriesRows{0};  ///< rows of <LABEL>.csv (magnetometer, IMU, odometry, ...)
    std::size_t frames{0};      ///< RGB-D frames written as PNG pairs
    std::size_t skipped{0};     ///< observations of the label with no export format
    std::string seriesFile;     ///< empty if no series was written
    std::string framesIndex;    ///< empty if no frame was written
};

/** Exports every observation labelled `label` from `rawlogPath` into `outDir` (created):
 * - classes with MRPT's text export (CObservationMagnetometer, CObservationIMU,
 *   CObservationOdometry, GPS, ...) as `<label>.csv`: `timestamp` [s] then the class's columns;
 * - CObservation3DRangeScan as `rgb/<n>.png` (8-bit colour) and `depth/<n>.png` (16-bit, raw
 *   rangeImage units) with the index `<label>_frames.csv` (timestamp, files, depth units [m]).
 * Throws std::runtime_error if the label never occurs (naming the labels that do), and
 * io::RawlogReadError on corrupt input after flushing everything read before the fault. */
SensorExportResult exportSensor(const std::string& rawlogPath, const std::string& label,
                                const std::string& outDir);

}  // namespace lodestone::inspect
