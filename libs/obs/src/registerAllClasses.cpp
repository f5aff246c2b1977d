#include <lodestone/obs/CObservationMagnetometer.h>
#include <lodestone/obs/CObservationWheelDrop.h>
#include <lodestone/obs/registerAllClasses.h>
#include <mrpt/rtti/CObject.h>

namespace lodestone {

void registerAllClasses() {
    mrpt::rtti::registerClass(CLASS_ID(lodestone::obs::CObservationMagnetometer));
    mrpt::rtti::registerClass(CLASS_ID(lodestone::obs::CObservationWheelDrop));
}

}  // namespace lodestone
