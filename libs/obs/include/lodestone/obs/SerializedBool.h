#pragma once
// A bool read from a rawlog as the byte it is: MRPT's `in >> bool` copies the raw byte into the
// bool, so a damaged one (any of 2..255) became an invalid bool (undefined behaviour; an export
// then wrote 127 into a 0/1 column). Anything but 0 or 1 is a read error naming the field.

#include <mrpt/serialization/CArchive.h>

#include <cstdint>
#include <stdexcept>
#include <string>

namespace lodestone::obs {

inline bool readBool(mrpt::serialization::CArchive& in, const char* className, const char* field) {
    std::uint8_t byte = 0;
    in >> byte;
    if (byte > 1) {
        throw std::runtime_error(std::string(className) + ": field '" + field + "' holds byte " +
                                 std::to_string(byte) + ", not a bool (0 or 1)");
    }
    return byte == 1;
}

}  // namespace lodestone::obs
