#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>

namespace lodestone::io {

/** A rawlog could not be read past some point. Names the file, the index of the entry that
 * failed (entries are counted from 0, as rawlog-edit does) and the byte offset in the
 * uncompressed stream where that entry starts. Entries before it were delivered. */
class RawlogReadError : public std::runtime_error {
  public:
    RawlogReadError(std::string file, std::size_t entryIndex, std::uint64_t byteOffset,
                    const std::string& reason);

    const std::string& file() const { return file_; }
    std::size_t entryIndex() const { return entry_index_; }
    std::uint64_t byteOffset() const { return byte_offset_; }
    const std::string& reason() const { return reason_; }

  private:
    std::string file_;
    std::size_t entry_index_;
    std::uint64_t byte_offset_;
    std::string reason_;
};

}  // namespace lodestone::io
