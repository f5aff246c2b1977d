#include <lodestone/io/EntryContents.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CSensoryFrame.h>

namespace lodestone::io {

using mrpt::obs::CObservation;

std::vector<CObservation::Ptr> observationsOf(
    const mrpt::serialization::CSerializable::Ptr& entry) {
    if (auto obs = std::dynamic_pointer_cast<CObservation>(entry)) return {obs};
    std::vector<CObservation::Ptr> out;
    if (auto sf = std::dynamic_pointer_cast<mrpt::obs::CSensoryFrame>(entry)) {
        for (const auto& o : *sf) {
            if (o) out.push_back(o);
        }
    }
    return out;
}

std::optional<mrpt::Clock::time_point> entryTimestamp(
    const mrpt::serialization::CSerializable& entry) {
    std::optional<mrpt::Clock::time_point> earliest;
    const auto consider = [&](mrpt::Clock::time_point t) {
        if (t == INVALID_TIMESTAMP) return;
        if (!earliest || t < *earliest) earliest = t;
    };
    if (const auto* obs = dynamic_cast<const CObservation*>(&entry)) {
        consider(obs->timestamp);
    } else if (const auto* sf = dynamic_cast<const mrpt::obs::CSensoryFrame*>(&entry)) {
        for (const auto& o : *sf) {
            if (o) consider(o->timestamp);
        }
    } else if (const auto* acts = dynamic_cast<const mrpt::obs::CActionCollection*>(&entry)) {
        for (const auto& a : *acts) consider(a->timestamp);
    }
    return earliest;
}

}  // namespace lodestone::io
