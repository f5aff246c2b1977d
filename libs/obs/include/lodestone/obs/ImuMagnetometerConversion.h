#pragma once

#include <lodestone/obs/CObservationMagnetometer.h>
#include <lodestone/obs/MagneticUnit.h>
#include <mrpt/obs/CObservationIMU.h>

namespace lodestone::obs {

/** True when `imu` carries all three magnetometer channels (IMU_MAG_X/Y/Z). */
bool hasMagnetometerChannels(const mrpt::obs::CObservationIMU& imu);

/** The magnetometer channels of `imu` as a CObservationMagnetometer, in uT.
 * Timestamp, label and sensor pose are kept; IMU_TEMPERATURE becomes `temperature`.
 * `calibrated` and `noiseStd` are not in CObservationIMU: the caller says them.
 * Throws std::invalid_argument if `imu` lacks a magnetometer channel. */
CObservationMagnetometer::Ptr magnetometerFromImu(const mrpt::obs::CObservationIMU& imu,
                                                  MagneticUnit imuUnit, bool calibrated = true,
                                                  const mrpt::math::TVector3D& noiseStd_uT = {0, 0,
                                                                                              0});

/** `mag` as a CObservationIMU carrying only IMU_MAG_X/Y/Z (and IMU_TEMPERATURE when known), in
 * `imuUnit` (gauss, as MRPT documents, by default), so stock MRPT tools can read the rawlog.
 * noiseStd and calibrated have no IMU field and are dropped. */
mrpt::obs::CObservationIMU::Ptr imuFromMagnetometer(const CObservationMagnetometer& mag,
                                                    MagneticUnit imuUnit = MagneticUnit::gauss());

}  // namespace lodestone::obs
