#pragma once

#include <mrpt/serialization/CSerializable.h>

#include <cstdint>
#include <memory>
#include <string>

namespace lodestone::io {

/** Writes a rawlog, plain or gzip-compressed, and pushes each entry to the file as soon as it
 * is written: a crash loses at most the entry being written, and the file
 * is a valid rawlog up to the last complete entry.
 *
 * The file is `path.partial` until close() - or the destructor, at the normal end of a scope -
 * renames it to `path`. A writer destroyed by an exception unwinding past it leaves the
 * `.partial` file, with everything written, and whatever was at `path` before untouched. */
class RawlogWriter {
  public:
    struct Options {
        int gzipLevel{0};  ///< 0: plain rawlog; 1..9: gzip level
    };

    /** Creates (truncates) `path.partial`; throws std::runtime_error naming it on failure. */
    explicit RawlogWriter(const std::string& path);
    RawlogWriter(const std::string& path, Options options);
    ~RawlogWriter();
    RawlogWriter(const RawlogWriter&) = delete;
    RawlogWriter& operator=(const RawlogWriter&) = delete;

    /** Appends one entry and flushes it. Entries are observations (observation-only format,
     * what Lodestone writes) or, to rewrite a stock rawlog keeping its layout, CSensoryFrame /
     * CActionCollection. Throws std::runtime_error (naming the file and the entry) on a write
     * error. */
    void write(const mrpt::serialization::CSerializable& entry);
    /** Finishes the file and renames it to path(); throws std::runtime_error on an error. */
    void close();

    const std::string& path() const { return path_; }
    std::size_t entriesWritten() const { return entries_written_; }

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
    std::string path_;
    std::size_t entries_written_{0};
    int uncaught_at_start_{0};  // std::uncaught_exceptions() when made: is the destructor unwinding?
};

}  // namespace lodestone::io
