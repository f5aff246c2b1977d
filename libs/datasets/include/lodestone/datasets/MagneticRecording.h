#pragma once

#include <lodestone/obs/MagneticUnit.h>
#include <mrpt/math/TPoint3D.h>

#include <string>
#include <vector>

namespace lodestone::datasets {

/** One sample of a real magnetometer recording with its reference trajectory: where the
 * carrier was (planar), which way it faced, and the field it measured expressed in its own
 * (levelled, heading-following) frame, as a robot's magnetometer sees it. */
struct MagneticRecordingSample {
    double t{0};                           ///< [s]
    double x{0}, y{0};                     ///< reference position [m]
    double heading{0};                     ///< reference heading [rad], continuous (unwrapped)
    mrpt::math::TVector3D field{0, 0, 0};  ///< [uT] in the carrier frame, z up
};

struct MagneticRecording {
    std::string name;  ///< e.g. "aalto/invensense trial 3"
    std::vector<MagneticRecordingSample> samples;
    bool calibrated{false};  ///< hard/soft-iron calibration already applied by the source
    /** Path length of the reference trajectory [m]. */
    double pathLength() const;
};

/** Aalto invensense trial (Solin et al. 2018): `DIR/N-time.csv`, `N-loc.csv` (x, y [m],
 * Vicon), `N-mag.csv` (field [uT] in the world frame), row-aligned. Aalto gives positions only:
 * the heading is the direction of travel (the robot drives forward), taken over
 * `headingBaseline` metres of path either side of a sample and held where the robot stands
 * still; the field is rotated into the robot frame with it. The field's numbers are in `unit`
 * (the dataset documents microtesla). Throws std::runtime_error naming the file and line on a
 * missing file, a bad number, a missing column or a row-count mismatch, and naming the file and
 * `--unit` when the field in that unit is not Earth's (requirePlausibleField). */
MagneticRecording readAaltoTrial(const std::string& dir, int trial, double headingBaseline = 0.05,
                                 const obs::MagneticUnit& unit = obs::MagneticUnit::microtesla());

/** Kok & Solin walk CSV: `t,tm,px,py,pz,q0,q1,q2,q3,mx,my,mz` (the header line first), field
 * in the device frame [uT], orientation a unit quaternion (w, x, y, z) of the device in the
 * world (z up). The field is levelled with the reference pitch and roll (inclination known,
 * heading not, as Kok & Solin do) so it is expressed in a frame that turns with the device's
 * heading only. The field's numbers are in `unit` (the dataset's: microtesla). Errors as
 * readAaltoTrial. */
MagneticRecording readKokWalk(const std::string& csvPath,
                              const obs::MagneticUnit& unit = obs::MagneticUnit::microtesla());

/** `recording` as readKokWalk reads it: a Kok & Solin CSV at `csvPath` with the field in `unit`
 * (the orientation the heading alone, the position at height 0). Throws std::runtime_error
 * naming the file on a write error. */
void writeKokWalk(const MagneticRecording& recording, const std::string& csvPath,
                  const obs::MagneticUnit& unit = obs::MagneticUnit::microtesla());

/** Throws std::runtime_error naming `source` and the option `--unit` when the recording's field
 * (converted to microtesla as read) cannot be Earth's (obs::implausibleFieldMagnitude): a
 * magnetometer in gauss or normalized units read as microtesla is refused before any work. */
void requirePlausibleField(const MagneticRecording& recording, const std::string& source);

}  // namespace lodestone::datasets
