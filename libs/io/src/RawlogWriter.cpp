#include <lodestone/io/RawlogPaths.h>
#include <lodestone/io/RawlogWriter.h>
#include <mrpt/serialization/CArchive.h>

#include <exception>
#include <filesystem>

#include "ZlibFileStream.h"

namespace lodestone::io {

struct RawlogWriter::Impl {
    Impl(const std::string& path, const Options& options)
        : stream(path,
                 options.gzipLevel > 0 ? detail::ZlibFileStream::Mode::WriteGzip
                                       : detail::ZlibFileStream::Mode::WritePlain,
                 options.gzipLevel),
          archive(mrpt::serialization::archiveFrom(stream)) {}
    detail::ZlibFileStream stream;
    mrpt::serialization::CArchiveStreamBase<detail::ZlibFileStream> archive;
    bool open{true};
};

RawlogWriter::RawlogWriter(const std::string& path) : RawlogWriter(path, Options{}) {}

namespace {
const std::string& checkedOutput(const std::string& path) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) throw std::runtime_error("output '" + path + "' is a folder");
    return path;
}
}  // namespace

RawlogWriter::RawlogWriter(const std::string& path, Options options)
    : impl_(std::make_unique<Impl>(partialPath(checkedOutput(path)), options)),
      path_(path),
      uncaught_at_start_(std::uncaught_exceptions()) {}

RawlogWriter::~RawlogWriter() {
    if (!impl_->open) return;
    try {
        if (std::uncaught_exceptions() > uncaught_at_start_) {
            impl_->stream.close();  // unwinding from an error: what was written stays in .partial
        } else {
            close();
        }
    } catch (...) {
        // A destructor cannot report; call close() to see write errors.
    }
}

void RawlogWriter::write(const mrpt::serialization::CSerializable& entry) {
    if (!impl_->open) throw std::logic_error(path_ + ": write after close");
    try {
        impl_->archive << entry;
        impl_->stream.flushToDisk();
    } catch (const std::exception& e) {
        throw std::runtime_error(path_ + ": cannot write entry " +
                                 std::to_string(entries_written_) + ": " + e.what());
    }
    ++entries_written_;
}

void RawlogWriter::close() {
    if (!impl_->open) return;
    impl_->open = false;
    impl_->stream.close();
    commitPartial(path_);
}

}  // namespace lodestone::io
