#pragma once

#include <lodestone/datasets/MagneticRecording.h>
#include <lodestone/datasets/SyntheticOdometry.h>

#include <string>

namespace lodestone::datasets {

struct MagneticImportResult {
    std::size_t magnetometerSamples{0}, odometrySamples{0};
    double duration{0};    ///< [s]
    double pathLength{0};  ///< reference [m]
    std::string rawlog, groundTruth;
};

/** Writes `recording` as an observation-only rawlog: a CObservationMagnetometer per sample
 * (label "MAG", field in the robot frame, sensor at the robot's origin) and a
 * CObservationOdometry (label "ODOMETRY", pose only, no encoders) per odometry sample from the
 * drift model; the reference trajectory goes beside it as OUT.gt.tum at the magnetometer's
 * timestamps. Throws std::runtime_error naming the file on a write error (entries already
 * written stay readable). */
MagneticImportResult writeMagneticRecording(const MagneticRecording& recording,
                                            const std::string& outRawlog,
                                            const OdometryDriftModel& model);

}  // namespace lodestone::datasets
