#pragma once

// Internal: an mrpt::io::CStream over rawlog bytes on disk. One class for the three ways
// Lodestone touches them: reading (plain or gzip, told from the content, through
// GzipFileReader), writing plain and writing gzip (a zlib gzFile). Unlike MRPT's CFileGZ*Stream it counts uncompressed bytes (for the
// byte offsets in error messages) and can flush to disk after each entry.

#include <mrpt/io/CStream.h>

#include <cstdint>
#include <memory>
#include <string>

#include "GzipFileReader.h"

namespace lodestone::io::detail {

class ZlibFileStream : public mrpt::io::CStream {
  public:
    enum class Mode { Read, WritePlain, WriteGzip };
    /** zlib's input buffer when reading: how far fileOffset() may run ahead [bytes]. */
    static constexpr unsigned kReadAhead = 1u << 17;

    /** Opens `path`; throws std::runtime_error naming the file on failure.
     * `gzipLevel` (1..9) is used in WriteGzip mode only. */
    ZlibFileStream(const std::string& path, Mode mode, int gzipLevel = 6);
    ~ZlibFileStream() override;
    ZlibFileStream(const ZlibFileStream&) = delete;
    ZlibFileStream& operator=(const ZlibFileStream&) = delete;

    size_t Read(void* buffer, size_t count) override;
    size_t Write(const void* buffer, size_t count) override;
    uint64_t Seek(int64_t offset, mrpt::io::CStream::TSeekOrigin origin) override;
    uint64_t getTotalBytesCount() const override;
    uint64_t getPosition() const override { return position_; }
    std::string getStreamDescription() const override { return path_; }

    /** Pushes everything written so far to the file, so a crash after this call loses
     * nothing before it (gzip: a sync flush point a reader can decompress up to). */
    void flushToDisk();
    /** Closes the file; throws std::runtime_error if zlib reports a write error. */
    void close();

    /** Bytes of the file on disk consumed so far (compressed bytes for gzip): for progress. */
    uint64_t fileOffset() const;
    /** True when reading a gzip-compressed file (false: plain). */
    bool isCompressed() const { return compressed_; }
    /** What stopped reading early (damaged or cut-short gzip data, garbage after it) or the
     * last zlib write error; empty if nothing. */
    const std::string& lastError() const { return last_error_; }

  private:
    std::unique_ptr<GzipFileReader> reader_;  // Mode::Read
    void* file_{nullptr};  // gzFile (writing), kept opaque so zlib.h stays out of this header
    std::string path_;
    Mode mode_;
    uint64_t position_{0};
    bool compressed_{false};
    std::string last_error_;
};

}  // namespace lodestone::io::detail
