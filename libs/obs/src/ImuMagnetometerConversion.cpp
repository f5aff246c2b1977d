#include <lodestone/obs/ImuMagnetometerConversion.h>

#include <stdexcept>

namespace lodestone::obs {

using mrpt::obs::CObservationIMU;

bool hasMagnetometerChannels(const CObservationIMU& imu) {
    return imu.has(mrpt::obs::IMU_MAG_X) && imu.has(mrpt::obs::IMU_MAG_Y) &&
           imu.has(mrpt::obs::IMU_MAG_Z);
}

CObservationMagnetometer::Ptr magnetometerFromImu(const CObservationIMU& imu, MagneticUnit imuUnit,
                                                  bool calibrated,
                                                  const mrpt::math::TVector3D& noiseStd_uT) {
    if (!hasMagnetometerChannels(imu)) {
        throw std::invalid_argument("CObservationIMU '" + imu.sensorLabel +
                                    "' has no IMU_MAG_X/Y/Z channels");
    }
    auto mag = CObservationMagnetometer::Create();
    mag->timestamp = imu.timestamp;
    mag->sensorLabel = imu.sensorLabel;
    mag->sensorPose = imu.sensorPose;
    const double k = imuUnit.microteslaPerUnit;
    mag->field = {k * imu.get(mrpt::obs::IMU_MAG_X), k * imu.get(mrpt::obs::IMU_MAG_Y),
                  k * imu.get(mrpt::obs::IMU_MAG_Z)};
    mag->noiseStd = noiseStd_uT;
    if (imu.has(mrpt::obs::IMU_TEMPERATURE)) {
        mag->temperature = imu.get(mrpt::obs::IMU_TEMPERATURE);
    }
    mag->calibrated = calibrated;
    return mag;
}

CObservationIMU::Ptr imuFromMagnetometer(const CObservationMagnetometer& mag,
                                         MagneticUnit imuUnit) {
    auto imu = CObservationIMU::Create();
    imu->timestamp = mag.timestamp;
    imu->sensorLabel = mag.sensorLabel;
    imu->sensorPose = mag.sensorPose;
    const double k = 1.0 / imuUnit.microteslaPerUnit;
    imu->set(mrpt::obs::IMU_MAG_X, k * mag.field.x);
    imu->set(mrpt::obs::IMU_MAG_Y, k * mag.field.y);
    imu->set(mrpt::obs::IMU_MAG_Z, k * mag.field.z);
    if (mag.temperature) imu->set(mrpt::obs::IMU_TEMPERATURE, *mag.temperature);
    return imu;
}

}  // namespace lodestone::obs
