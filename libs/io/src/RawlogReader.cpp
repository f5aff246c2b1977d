#include <lodestone/io/RawlogReadError.h>
#include <lodestone/io/RawlogReader.h>
#include <mrpt/serialization/CArchive.h>

#include <algorithm>
#include <filesystem>

#include "ZlibFileStream.h"

namespace lodestone::io {

namespace {
// MRPT exception texts carry a multi-line call trace; the first line that says what went
// wrong is what a user needs.
std::string firstMeaningfulLine(const std::string& text) {
    std::size_t start = 0;
    while (start < text.size()) {
        std::size_t end = text.find('\n', start);
        if (end == std::string::npos) end = text.size();
        std::string line = text.substr(start, end - start);
        const auto first = line.find_first_not_of(" \t=");
        if (first != std::string::npos && line.find("MRPT exception") == std::string::npos) {
            return line.substr(first);
        }
        start = end + 1;
    }
    return text;
}
}  // namespace

struct RawlogReader::Impl {
    explicit Impl(const std::string& path)
        : stream(path, detail::ZlibFileStream::Mode::Read),
          archive(mrpt::serialization::archiveFrom(stream)) {}
    detail::ZlibFileStream stream;
    mrpt::serialization::CArchiveStreamBase<detail::ZlibFileStream> archive;
};

RawlogReader::RawlogReader(const std::string& path) : path_(path) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) {
        throw std::runtime_error(path + ": no such rawlog file");
    }
    file_size_ = std::filesystem::file_size(path, ec);
    impl_ = std::make_unique<Impl>(path);
    compressed_ = impl_->stream.isCompressed();
}

RawlogReader::~RawlogReader() = default;

std::uint64_t RawlogReader::bytesRead() const { return impl_->stream.getPosition(); }

double RawlogReader::fractionRead() const {
    if (file_size_ == 0) return 1.0;
    return std::min(1.0, static_cast<double>(impl_->stream.fileOffset()) / file_size_);
}

std::optional<RawlogEntry> RawlogReader::next() {
    if (failed_) return std::nullopt;
    RawlogEntry entry;
    entry.index = next_index_;
    entry.byteOffset = impl_->stream.getPosition();
    const auto fail = [&](const std::string& reason) {
        failed_ = true;
        std::string why = reason;
        const std::string& zlibError = impl_->stream.lastError();
        if (!zlibError.empty()) why += " (zlib: " + zlibError + ")";
        return RawlogReadError(path_, entry.index, entry.byteOffset, why);
    };
    try {
        entry.object = impl_->archive.ReadObject();
    } catch (const mrpt::serialization::CExceptionEOF&) {
        if (impl_->stream.getPosition() == entry.byteOffset && impl_->stream.lastError().empty()) {
            return std::nullopt;  // a clean end between two entries
        }
        throw fail("truncated: the file ends inside this entry");
    } catch (const std::bad_alloc&) {
        throw fail("corrupt entry (an impossible size made the reader run out of memory)");
    } catch (const std::exception& e) {
        throw fail(firstMeaningfulLine(e.what()));
    }
    if (!entry.object) throw fail("null object stored as an entry");
    ++next_index_;
    return entry;
}

}  // namespace lodestone::io
