#pragma once

#include <mrpt/math/TPoint3D.h>
#include <mrpt/obs/CObservation.h>
#include <mrpt/poses/CPose3D.h>
#include <mrpt/serialization/CSerializable.h>

#include <optional>

namespace lodestone::obs {

/** One three-axis magnetometer reading.
 *
 * The field is expressed in the sensor frame, whose pose on the robot is `sensorPose`.
 * Serialization is versioned (see serializeGetVersion): every version ever written stays
 * readable, and tests/data holds a golden file for each.
 *
 * Stock MRPT tools read a rawlog holding this class once they load Lodestone's MRPT plugin
 * (`RawLogViewer -l`, `rawlog-edit -p`: plugins/mrpt); without it they abort (MRPT archives
 * have no per-object length to skip it). `lodestone-inspect to-imu` rewrites such a rawlog with
 * CObservationIMU magnetometer channels instead (see ImuMagnetometerConversion.h).
 */
class CObservationMagnetometer : public mrpt::obs::CObservation {
    DEFINE_SERIALIZABLE(CObservationMagnetometer, lodestone::obs)

  public:
    CObservationMagnetometer() = default;

    mrpt::poses::CPose3D sensorPose;          ///< sensor frame on the robot frame
    mrpt::math::TVector3D field{0, 0, 0};     ///< field in the sensor frame [uT]
    mrpt::math::TVector3D noiseStd{0, 0, 0};  ///< per-axis white-noise standard deviation [uT]
    std::optional<double> temperature;        ///< sensor temperature, when reported [degC]
    bool calibrated{false};  ///< hard/soft-iron calibration already applied to `field`

    /** |field| [uT]. */
    double magnitude() const;

    void getSensorPose(mrpt::poses::CPose3D& out_sensorPose) const override {
        out_sensorPose = sensorPose;
    }
    void setSensorPose(const mrpt::poses::CPose3D& newSensorPose) override {
        sensorPose = newSensorPose;
    }
    void getDescriptionAsText(std::ostream& o) const override;

    bool exportTxtSupported() const override { return true; }
    std::string exportTxtHeader() const override;
    std::string exportTxtDataRow() const override;
};

}  // namespace lodestone::obs
