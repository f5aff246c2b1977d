#include <lodestone/inspect/MagnetometerToImu.h>
#include <lodestone/io/RawlogPaths.h>
#include <lodestone/io/RawlogReader.h>
#include <lodestone/io/RawlogWriter.h>
#include <lodestone/obs/CObservationWheelDrop.h>
#include <lodestone/obs/ImuMagnetometerConversion.h>
#include <mrpt/obs/CObservationComment.h>
#include <mrpt/obs/CSensoryFrame.h>

namespace lodestone::inspect {

MagnetometerToImuResult magnetometersToImu(const std::string& inPath, const std::string& outPath,
                                           lodestone::obs::MagneticUnit imuUnit) {
    using lodestone::obs::CObservationMagnetometer;
    io::refuseOutputOverInput(outPath, {inPath});
    io::RawlogReader reader(inPath);
    io::RawlogWriter writer(outPath, {io::isGzipPath(outPath) ? 6 : 0});
    MagnetometerToImuResult result;
    const auto convert =
        [&](const mrpt::obs::CObservation::Ptr& obs) -> mrpt::obs::CObservation::Ptr {
        if (auto mag = std::dynamic_pointer_cast<CObservationMagnetometer>(obs)) {
            ++result.converted;
            return lodestone::obs::imuFromMagnetometer(*mag, imuUnit);
        }
        if (auto drop = std::dynamic_pointer_cast<lodestone::obs::CObservationWheelDrop>(obs)) {
            // MRPT has no wheel-drop class: keep the event as a comment stock tools can show.
            auto comment = mrpt::obs::CObservationComment::Create();
            comment->timestamp = drop->timestamp;
            comment->sensorLabel = drop->sensorLabel;
            // (A comment's serialization drops the label: it goes into the text as well.)
            comment->text = drop->sensorLabel +
                            " wheel drop: left=" + (drop->leftDropped ? "1" : "0") +
                            " right=" + (drop->rightDropped ? "1" : "0");
            ++result.commented;
            return comment;
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
