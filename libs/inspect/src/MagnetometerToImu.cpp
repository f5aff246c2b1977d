#include <lodestone/inspect/MagnetometerToImu.h>
#include <lodestone/io/RawlogReader.h>
#include <lodestone/io/RawlogWriter.h>
#include <lodestone/obs/ImuMagnetometerConversion.h>
#include <mrpt/obs/CSensoryFrame.h>

namespace lodestone::inspect {

namespace {
bool endsWith(const std::string& s, const std::string& suffix) {
    return s.size() >= suffix.size() &&
           s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}
}  // namespace

MagnetometerToImuResult magnetometersToImu(const std::string& inPath, const std::string& outPath,
                                           lodestone::obs::MagneticUnit imuUnit) {
    using lodestone::obs::CObservationMagnetometer;
    io::RawlogReader reader(inPath);
    io::RawlogWriter writer(outPath, {endsWith(outPath, ".gz") ? 6 : 0});
    MagnetometerToImuResult result;
    const auto convert =
        [&](const mrpt::obs::CObservation::Ptr& obs) -> mrpt::obs::CObservation::Ptr {
        if (auto mag = std::dynamic_pointer_cast<CObservationMagnetometer>(obs)) {
            ++result.converted;
            return lodestone::obs::imuFromMagnetometer(*mag, imuUnit);
        }
        return obs;
    };
    while (auto entry = reader.next()) {
        if (auto obs = std::dynamic_pointer_cast<mrpt::obs::CObservation>(entry->object)) {
            writer.write(*convert(obs));
        } else if (auto sf = std::dynamic_pointer_cast<mrpt::obs::CSensoryFrame>(entry->object)) {
            mrpt::obs::CSensoryFrame rewritten;
            for (const auto& o : *sf) {
                if (o) rewritten.insert(convert(o));
            }
            writer.write(rewritten);
        } else {
            writer.write(*entry->object);
        }
        ++result.entries;
    }
    writer.close();
    return result;
}

}  // namespace lodestone::inspect
