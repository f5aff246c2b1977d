#pragma once

#include <mrpt/obs/CObservation.h>
#include <mrpt/serialization/CSerializable.h>

namespace lodestone::obs {

/** The wheel-drop switches of a mobile base (a Kobuki reports one per wheel): a wheel drops when
 * the robot is lifted off the floor. Lodestone's kidnap detection listens to it. Emitted when
 * the state changes. MRPT has no class for it. Versioned serialization, as
 * CObservationMagnetometer. */
class CObservationWheelDrop : public mrpt::obs::CObservation {
    DEFINE_SERIALIZABLE(CObservationWheelDrop, lodestone::obs)

  public:
    bool leftDropped{false};   ///< left wheel hangs free
    bool rightDropped{false};  ///< right wheel hangs free

    /** True when either wheel is dropped: the robot is (being) lifted. */
    bool lifted() const { return leftDropped || rightDropped; }

    void getSensorPose(mrpt::poses::CPose3D& out_sensorPose) const override {
        out_sensorPose = mrpt::poses::CPose3D();
    }
    void setSensorPose(const mrpt::poses::CPose3D&) override {}
    void getDescriptionAsText(std::ostream& o) const override;

    bool exportTxtSupported() const override { return true; }
    std::string exportTxtHeader() const override;
    std::string exportTxtDataRow() const override;
};

}  // namespace lodestone::obs
