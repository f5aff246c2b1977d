#pragma once

#include <mrpt/serialization/CSerializable.h>

#include <string>

namespace lodestone::io {

/** The two rawlog layouts MRPT writes, as told by the entries seen so far. */
enum class RawlogFormat {
    Empty,                 ///< no entry yet
    Observations,          ///< observation-only: each entry is one CObservation
    ActionsSensoryFrames,  ///< CActionCollection / CSensoryFrame entries
    Mixed                  ///< both kinds of entries (legal for MRPT, rare)
};

/** Updates `format` with one more top-level entry. */
RawlogFormat updateFormat(RawlogFormat format, const mrpt::serialization::CSerializable& entry);

std::string toString(RawlogFormat format);

}  // namespace lodestone::io
