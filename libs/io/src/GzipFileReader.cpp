#include "GzipFileReader.h"

#include <zlib.h>

#include <algorithm>
#include <cstring>
#include <limits>
#include <stdexcept>

namespace lodestone::io::detail {

struct GzipFileReader::Inflater {
    z_stream stream{};
};

GzipFileReader::GzipFileReader(const std::string& path, std::size_t bufferBytes)
    : path_(path), in_(std::max<std::size_t>(bufferBytes, 16)) {
    file_ = std::fopen(path.c_str(), "rb");
    if (!file_) throw std::runtime_error(path + ": cannot open for reading");
    fill(2);
    compressed_ = inEnd_ - inStart_ >= 2 && in_[inStart_] == 0x1f && in_[inStart_ + 1] == 0x8b;
    if (compressed_) {
        z_ = std::make_unique<Inflater>();
        if (inflateInit2(&z_->stream, 15 + 16) != Z_OK) {  // 15 + 16: gzip framing only
            std::fclose(file_);
            throw std::runtime_error(path + ": zlib inflateInit2 failed");
        }
    }
}

GzipFileReader::~GzipFileReader() {
    if (z_) inflateEnd(&z_->stream);
    if (file_) std::fclose(file_);
}

bool GzipFileReader::fill(std::size_t atLeast) {
    if (inStart_ > 0) {  // keep what is unconsumed at the front
        std::memmove(in_.data(), in_.data() + inStart_, inEnd_ - inStart_);
        inEnd_ -= inStart_;
        inStart_ = 0;
    }
    while (inEnd_ < atLeast && inEnd_ < in_.size()) {
        const std::size_t n = std::fread(in_.data() + inEnd_, 1, in_.size() - inEnd_, file_);
        if (n == 0) break;
        inEnd_ += n;
        fileRead_ += n;
    }
    return inEnd_ >= atLeast;
}

std::uint64_t GzipFileReader::fileOffset() const { return fileRead_ - (inEnd_ - inStart_); }

std::size_t GzipFileReader::read(void* buffer, std::size_t count) {
    if (failed_ || count == 0) return 0;
    return compressed_ ? readGzip(static_cast<unsigned char*>(buffer), count) : readPlain(buffer, count);
}

std::size_t GzipFileReader::readPlain(void* buffer, std::size_t count) {
    auto* out = static_cast<unsigned char*>(buffer);
    std::size_t total = std::min(count, inEnd_ - inStart_);
    std::memcpy(out, in_.data() + inStart_, total);
    inStart_ += total;
    while (total < count) {
        const std::size_t n = std::fread(out + total, 1, count - total, file_);
        if (n == 0) break;
        total += n;
        fileRead_ += n;
    }
    return total;
}

std::size_t GzipFileReader::readGzip(unsigned char* out, std::size_t count) {
    z_stream& z = z_->stream;
    std::size_t total = 0;
    while (total < count) {
        if (memberEnded_) {
            // After a member: the end of the file, another member, or garbage.
            if (!fill(2)) {
                if (inEnd_ == inStart_) return total;  // the clean end
            }
            if (inEnd_ - inStart_ < 2 || in_[inStart_] != 0x1f || in_[inStart_ + 1] != 0x8b) {
                error_ = "garbage after the end of the gzip data (at file byte " +
                         std::to_string(fileOffset()) + ")";
                failed_ = true;
                return total;
            }
            inflateReset(&z);
            memberEnded_ = false;
        }
        if (inStart_ == inEnd_ && !fill(1)) {
            error_ = "unexpected end of file (the gzip data is cut short)";
            failed_ = true;
            return total;
        }
        z.next_in = in_.data() + inStart_;
        z.avail_in = static_cast<uInt>(inEnd_ - inStart_);
        z.next_out = out + total;
        z.avail_out = static_cast<uInt>(std::min<std::size_t>(count - total, std::numeric_limits<uInt>::max()));
        const uInt outBefore = z.avail_out;
        const int rc = inflate(&z, Z_NO_FLUSH);
        inStart_ = inEnd_ - z.avail_in;
        total += outBefore - z.avail_out;
        if (rc == Z_STREAM_END) {
            memberEnded_ = true;
        } else if (rc == Z_BUF_ERROR) {
            // No progress possible: more input is needed (avail_in is 0) - the loop refills.
            if (z.avail_in != 0) {
                error_ = "zlib could not make progress";
                failed_ = true;
                return total;
            }
        } else if (rc != Z_OK) {
            error_ = std::string("damaged gzip data: ") + (z.msg ? z.msg : "zlib error " + std::to_string(rc));
            failed_ = true;
            return total;
        }
    }
    return total;
}

}  // namespace lodestone::io::detail
