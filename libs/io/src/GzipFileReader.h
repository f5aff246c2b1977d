#pragma once

// Internal: reads a file that is either plain or gzip (told from its first two bytes), with
// zlib's inflate driven directly rather than through gzread, so the end of the compressed
// data is known: concatenated gzip members are read on, and anything else after the last
// member is an error ("garbage after the end of the gzip data"), where gzread ignores it.

#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

namespace lodestone::io::detail {

class GzipFileReader {
  public:
    /** Opens `path`; throws std::runtime_error naming it if it cannot be opened.
     * `bufferBytes`: the compressed input read at a time. */
    GzipFileReader(const std::string& path, std::size_t bufferBytes);
    ~GzipFileReader();
    GzipFileReader(const GzipFileReader&) = delete;
    GzipFileReader& operator=(const GzipFileReader&) = delete;

    /** Up to `count` bytes of data; fewer only at the end of the data or on an error
     * (then error() says what). */
    std::size_t read(void* buffer, std::size_t count);
    bool isCompressed() const { return compressed_; }
    /** Bytes of the file consumed so far (compressed bytes for gzip). */
    std::uint64_t fileOffset() const;
    /** What stopped the reading early (damaged or truncated data, trailing garbage), or empty. */
    const std::string& error() const { return error_; }

  private:
    bool fill(std::size_t atLeast);
    std::size_t readPlain(void* buffer, std::size_t count);
    std::size_t readGzip(unsigned char* out, std::size_t count);

    std::string path_;
    std::FILE* file_{nullptr};
    bool compressed_{false};
    bool member_ended_{false};  // between two gzip members (or at the end of the last)
    bool failed_{false};
    std::vector<unsigned char> in_;
    std::size_t in_start_{0}, in_end_{0};  // unconsumed input: in_[in_start_, in_end_)
    std::uint64_t file_read_{0};          // bytes read from the file into in_
    struct Inflater;
    std::unique_ptr<Inflater> z_;
    std::string error_;
};

}  // namespace lodestone::io::detail
