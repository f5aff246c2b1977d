#pragma once

#include <mrpt/obs/CObservation.h>
#include <mrpt/serialization/CSerializable.h>

#include <optional>
#include <vector>

namespace lodestone::io {

/** The observations inside one top-level rawlog entry: the entry itself if it is an
 * observation, the frame's observations if it is a CSensoryFrame, none otherwise (actions). */
std::vector<mrpt::obs::CObservation::Ptr> observationsOf(
    const mrpt::serialization::CSerializable::Ptr& entry);

/** When an entry happened: an observation's timestamp, the earliest timestamp in a sensory
 * frame or action collection; nullopt if it holds no valid timestamp. */
std::optional<mrpt::Clock::time_point> entryTimestamp(
    const mrpt::serialization::CSerializable& entry);

}  // namespace lodestone::io
