#include <lodestone/io/RawlogFormat.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CObservation.h>
#include <mrpt/obs/CSensoryFrame.h>

namespace lodestone::io {

RawlogFormat updateFormat(RawlogFormat format, const mrpt::serialization::CSerializable& entry) {
    const bool isSfEntry =
        IS_CLASS(entry, mrpt::obs::CActionCollection) || IS_CLASS(entry, mrpt::obs::CSensoryFrame);
    const RawlogFormat kind =
        isSfEntry ? RawlogFormat::ActionsSensoryFrames : RawlogFormat::Observations;
    if (format == RawlogFormat::Empty) return kind;
    return format == kind ? format : RawlogFormat::Mixed;
}

std::string toString(RawlogFormat format) {
    switch (format) {
        case RawlogFormat::Empty:
            return "empty";
        case RawlogFormat::Observations:
            return "observations only";
        case RawlogFormat::ActionsSensoryFrames:
            return "actions + sensory frames";
        case RawlogFormat::Mixed:
            return "mixed (observations and actions + sensory frames)";
    }
    return "unknown";
}

}  // namespace lodestone::io
