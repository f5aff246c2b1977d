#pragma once

#include <mrpt/serialization/CSerializable.h>

#include <cstdint>
#include <memory>
#include <string>

namespace lodestone::io {

/** Writes a rawlog, plain or gzip-compressed, and pushes each entry to the file as soon as it
 * is written: a crash loses at most the entry being written, and the file
 * is a valid rawlog up to the last complete entry. */
class RawlogWriter {
  public:
    struct Options {
        int gzipLevel{0};  ///< 0: plain rawlog; 1..9: gzip level
    };

    /** Creates (truncates) `path`; throws std::runtime_error naming it on failure. */
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
    /** Finishes the file; also done by the destructor (which cannot report errors). */
    void close();

    const std::string& path() const { return path_; }
    std::size_t entriesWritten() const { return entries_written_; }

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
    std::string path_;
    std::size_t entries_written_{0};
};

}  // namespace lodestone::io
