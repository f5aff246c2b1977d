#include <lodestone/io/RawlogReadError.h>

namespace lodestone::io {

RawlogReadError::RawlogReadError(std::string file, std::size_t entryIndex, std::uint64_t byteOffset,
                                 const std::string& reason)
    : std::runtime_error(file + ": entry " + std::to_string(entryIndex) + " at byte offset " +
                         std::to_string(byteOffset) + ": " + reason),
      file_(std::move(file)),
      entry_index_(entryIndex),
      byte_offset_(byteOffset),
      reason_(reason) {}

}  // namespace lodestone::io
