#pragma once

#include <mrpt/serialization/CSerializable.h>

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

namespace lodestone::io {

/** One top-level object of a rawlog: an observation (observation-only format), or a
 * CActionCollection / CSensoryFrame (actions + sensory frames format). */
struct RawlogEntry {
    std::size_t index{0};         ///< position in the file, from 0
    std::uint64_t byteOffset{0};  ///< where the entry starts in the uncompressed stream [bytes]
    mrpt::serialization::CSerializable::Ptr object;
};

/** Reads the top-level entries of a rawlog one at a time, plain or gzip-compressed (detected
 * from the content, not the name). Holds one entry in memory at a time, so a file of any
 * length reads in flat memory.
 *
 * A truncated file, garbage bytes or an unregistered class stop the reading with a
 * RawlogReadError naming the file, the failing entry and its byte offset; every entry before
 * it has been returned. Call lodestone::registerAllClasses() before reading our rawlogs. */
class RawlogReader {
  public:
    /** Opens `path`; throws std::runtime_error naming the file if it cannot be opened. */
    explicit RawlogReader(const std::string& path);
    ~RawlogReader();
    RawlogReader(const RawlogReader&) = delete;
    RawlogReader& operator=(const RawlogReader&) = delete;

    /** The next entry, or std::nullopt at a clean end of file. Throws RawlogReadError. */
    std::optional<RawlogEntry> next();

    const std::string& path() const { return path_; }
    /** Bytes of the uncompressed stream consumed so far. */
    std::uint64_t bytesRead() const;
    /** How far through the file on disk the reader is, 0..1 (for progress bars). */
    double fractionRead() const;
    /** Size of the file on disk [bytes]. */
    std::uint64_t fileSize() const { return file_size_; }
    bool isCompressed() const { return compressed_; }

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
    std::string path_;
    std::uint64_t file_size_{0};
    bool compressed_{false};
    std::size_t next_index_{0};
    bool failed_{false};
};

}  // namespace lodestone::io
