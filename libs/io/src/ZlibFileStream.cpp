#include "ZlibFileStream.h"

#include <zlib.h>

#include <cstdio>
#include <limits>
#include <stdexcept>

namespace lodestone::io::detail {

namespace {
gzFile asGz(void* f) { return static_cast<gzFile>(f); }

std::string gzErrorText(void* f) {
    int code = 0;
    const char* text = gzerror(asGz(f), &code);
    return (code != Z_OK && text) ? std::string(text) : std::string();
}
}  // namespace

ZlibFileStream::ZlibFileStream(const std::string& path, Mode mode, int gzipLevel)
    : path_(path), mode_(mode) {
    if (mode == Mode::Read) {
        reader_ = std::make_unique<GzipFileReader>(path, kReadAhead);
        compressed_ = reader_->isCompressed();
        return;
    }
    std::string openMode = "wbT";  // 'T': transparent, i.e. no gzip framing
    if (mode == Mode::WriteGzip) {
        if (gzipLevel < 1 || gzipLevel > 9) {
            throw std::invalid_argument(path + ": gzip level must be 1..9, got " +
                                        std::to_string(gzipLevel));
        }
        openMode = "wb" + std::to_string(gzipLevel);
    }
    file_ = gzopen(path.c_str(), openMode.c_str());
    if (!file_) throw std::runtime_error(path + ": cannot open for writing");
}

ZlibFileStream::~ZlibFileStream() {
    if (file_) gzclose(asGz(file_));
}

size_t ZlibFileStream::Read(void* buffer, size_t count) {
    if (mode_ != Mode::Read || !reader_) return 0;
    const size_t n = reader_->read(buffer, count);
    last_error_ = reader_->error();
    position_ += n;
    return n;
}

size_t ZlibFileStream::Write(const void* buffer, size_t count) {
    if (mode_ == Mode::Read || !file_) return 0;
    size_t total = 0;
    const auto* in = static_cast<const char*>(buffer);
    while (total < count) {
        const unsigned chunk = static_cast<unsigned>(std::min<size_t>(count - total, 1u << 30));
        const int n = gzwrite(asGz(file_), in + total, chunk);
        if (n <= 0) {
            last_error_ = gzErrorText(file_);
            break;
        }
        total += static_cast<size_t>(n);
    }
    position_ += total;
    return total;
}

uint64_t ZlibFileStream::Seek(int64_t, mrpt::io::CStream::TSeekOrigin) {
    throw std::logic_error(path_ + ": ZlibFileStream does not seek");
}

uint64_t ZlibFileStream::fileOffset() const {
    if (reader_) return reader_->fileOffset();
    const auto off = gzoffset(asGz(file_));
    return off < 0 ? 0 : static_cast<uint64_t>(off);
}

uint64_t ZlibFileStream::getTotalBytesCount() const {
    return std::numeric_limits<uint64_t>::max();  // unknown for a gzip stream
}

void ZlibFileStream::flushToDisk() {
    if (!file_ || mode_ == Mode::Read) return;
    if (gzflush(asGz(file_), Z_SYNC_FLUSH) != Z_OK) {
        throw std::runtime_error(path_ + ": write error: " + gzErrorText(file_));
    }
}

void ZlibFileStream::close() {
    reader_.reset();
    if (!file_) return;
    const int rc = gzclose(asGz(file_));
    file_ = nullptr;
    if (rc != Z_OK && mode_ != Mode::Read) {
        throw std::runtime_error(path_ + ": error closing file (zlib code " + std::to_string(rc) +
                                 ")");
    }
}

}  // namespace lodestone::io::detail
