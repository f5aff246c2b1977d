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
    compressed_ = in_end_ - in_start_ >= 2 && in_[in_start_] == 0x1f && in_[in_start_ + 1] == 0x8b;
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
    if (in_start_ > 0) {  // keep what is unconsumed at the front
        std::memmove(in_.data(), in_.data() + in_start_, in_end_ - in_start_);
        in_end_ -= in_start_;
        in_start_ = 0;
    }
    while (in_end_ < atLeast && in_end_ < in_.size()) {
        const std::size_t n = std::fread(in_.data() + in_end_, 1, in_.size() - in_end_, file_);
        if (n == 0) break;
        in_end_ += n;
        file_read_ += n;
    }
    return in_end_ >= atLeast;
}

std::uint64_t GzipFileReader::fileOffset() const { return file_read_ - (in_end_ - in_start_); }

std::size_t GzipFileReader::read(void* buffer, std::size_t count) {
    if (failed_ || count == 0) return 0;
    return compressed_ ? readGzip(static_cast<unsigned char*>(buffer), count) : readPlain(buffer, count);
}

std::size_t GzipFileReader::readPlain(void* buffer, std::size_t count) {
    auto* out = static_cast<unsigned char*>(buffer);
    std::size_t total = std::min(count, in_end_ - in_start_);
    std::memcpy(out, in_.data() + in_start_, total);
    in_start_ += total;
    while (total < count) {
        const std::size_t n = std::fread(out + total, 1, count - total, file_);
        if (n == 0) break;
        total += n;
        file_read_ += n;
    }
    return total;
}

std::size_t GzipFileReader::readGzip(unsigned char* out, std::size_t count) {
    z_stream& z = z_->stream;
    std::size_t total = 0;
    while (total < count) {
        if (member_ended_) {
            // After a member: the end of the file, another member, or garbage.
            if (!fill(2)) {
                if (in_end_ == in_start_) return total;  // the clean end
            }
            if (in_end_ - in_start_ < 2 || in_[in_start_] != 0x1f || in_[in_start_ + 1] != 0x8b) {
                error_ = "garbage after the end of the gzip data (at file byte " +
                         std::to_string(fileOffset()) + ")";
                failed_ = true;
                return total;
            }
            inflateReset(&z);
            member_ended_ = false;
        }
        if (in_start_ == in_end_ && !fill(1)) {
            error_ = "unexpected end of file (the gzip data is cut short)";
            failed_ = true;
            return total;
        }
        z.next_in = in_.data() + in_start_;
        z.avail_in = static_cast<uInt>(in_end_ - in_start_);
        z.next_out = out + total;
        z.avail_out = static_cast<uInt>(std::min<std::size_t>(count - total, std::numeric_limits<uInt>::max()));
        const uInt outBefore = z.avail_out;
        const int rc = inflate(&z, Z_NO_FLUSH);
        in_start_ = in_end_ - z.avail_in;
        total += outBefore - z.avail_out;
        if (rc == Z_STREAM_END) {
            member_ended_ = true;
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
