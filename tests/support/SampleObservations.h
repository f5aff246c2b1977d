#pragma once

// Deterministic observations of every kind Lodestone reads, for tests and for the bundled
// sample rawlog: a robot driving a circle past a magnetic anomaly, with two magnetometers, an
// IMU, wheel encoders and a small RGB-D camera.

#include <lodestone/obs/CObservationMagnetometer.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/obs/CObservationIMU.h>
#include <mrpt/obs/CObservationOdometry.h>

#include <string>
#include <vector>

namespace lodestone::test {

lodestone::obs::CObservationMagnetometer::Ptr makeMagnetometer(double t, const std::string& label,
                                                               double seedValue);
mrpt::obs::CObservationIMU::Ptr makeImu(double t, const std::string& label, double seedValue);
mrpt::obs::CObservationOdometry::Ptr makeOdometry(double t, double seedValue);
/** A `width` x `height` RGB-D frame of a textured wall; `seedValue` shifts the texture. */
mrpt::obs::CObservation3DRangeScan::Ptr makeRangeScan(double t, int width, int height,
                                                      double seedValue);

struct SampleDriveOptions {
    double duration{10.0};  ///< [s]
    double t0{1.7e9};       ///< first timestamp [s since epoch]
    double magnetometerRate{100.0}, imuRate{100.0}, odometryRate{50.0}, cameraRate{5.0};  ///< [Hz]
    int cameraWidth{80}, cameraHeight{60};                                                ///< [px]
};

/** The whole drive, sorted by timestamp (ties broken by a fixed sensor order). */
std::vector<mrpt::obs::CObservation::Ptr> makeSampleDrive(const SampleDriveOptions& options);

/** True when both serialize to the same bytes: exact equality for any MRPT object. */
bool serializeEqual(const mrpt::serialization::CSerializable& a,
                    const mrpt::serialization::CSerializable& b);

}  // namespace lodestone::test
