#pragma once

#include <mrpt/obs/CObservation.h>
#include <mrpt/serialization/CSerializable.h>

#include <ostream>
#include <string>

namespace lodestone::inspect {

/** One line of what an observation holds, e.g. "B=(20.1, -3.5, -44.2) uT |B|=48.7" or
 * "640x480 depth 92% valid, RGB". Empty for classes it knows nothing about. */
std::string shortContent(const mrpt::obs::CObservation& obs);

/** The line `lodestone-inspect list` prints for an observation: time, class, label, content. */
std::string observationLine(const mrpt::obs::CObservation& obs);

/** The full text description of a top-level entry (each observation of a sensory frame, each
 * action of an action collection), as RawLogViewer shows it. */
void describeEntry(const mrpt::serialization::CSerializable& entry, std::ostream& out);

}  // namespace lodestone::inspect
