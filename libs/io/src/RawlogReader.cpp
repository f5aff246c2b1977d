#include <lodestone/io/RawlogReadError.h>
#include <lodestone/memguard/AllocationBudget.h>
#include <lodestone/io/RawlogReader.h>
#include <mrpt/serialization/CArchive.h>

#include <algorithm>
#include <filesystem>

#include "ZlibFileStream.h"
#include <lodestone/io/MrptErrorText.h>

#include "guards/EntryChecks.h"
#include "guards/GuardedMrptClasses.h"

namespace lodestone::io {

namespace {
// What reading one entry may allocate (memguard::AllocationBudget): MRPT allocates what an
// entry's size fields say before reading the data, so a damaged size would take gigabytes.
// Real data needs its bytes in the file, so the bound is a multiple of what is left of it:
constexpr std::uint64_t kEntryFloor = 64ull << 20;  // MRPT's own bookkeeping, small entries
constexpr std::uint64_t kBytesPerStoredByte = 8;    // conversions on load (e.g. 16-bit -> float)
constexpr std::uint64_t kMaxDeflateRatio = 1032;    // deflate's limit: gzip bytes -> data bytes
constexpr std::uint64_t kMaxEntryBytes = 2ull << 30;  // whatever the file: 2 GiB an entry

std::string megabytes(std::uint64_t bytes) {
    return std::to_string((bytes + (1 << 20) - 1) >> 20) + " MB";
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
    detail::installGuardedMrptClasses();
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
    // MRPT reports a refused allocation in several ways (bad_alloc, wrapped in its own
    // exception, or a failure further on): the budget says what happened.
    // Bytes of the file that may still hold this entry: in a plain file, from where it starts;
    // in a gzip file, from where zlib has read to, less its read-ahead buffer.
    std::uint64_t offset = entry.byteOffset;
    if (compressed_) {
        const std::uint64_t read = impl_->stream.fileOffset();
        offset = read > detail::ZlibFileStream::kReadAhead ? read - detail::ZlibFileStream::kReadAhead : 0;
    }
    const std::uint64_t left = file_size_ > offset ? file_size_ - offset : 0;
    const std::uint64_t limit =
        std::min(kMaxEntryBytes,
                 kEntryFloor + kBytesPerStoredByte * (compressed_ ? kMaxDeflateRatio : 1) * left);
    memguard::AllocationBudget budget(limit);
    const auto overBudget = [&] {
        return fail("corrupt entry: a size field asks for " + megabytes(budget.refused()) +
                    ", more than the " + std::to_string(left) + (compressed_ ? " compressed" : "") +
                    " bytes left in the file can hold (limit " + megabytes(limit) + ")");
    };
    try {
        entry.object = impl_->archive.ReadObject();
        if (budget.exceeded()) throw overBudget();
    } catch (const RawlogReadError&) {
        throw;
    } catch (const mrpt::serialization::CExceptionEOF&) {
        if (budget.exceeded()) throw overBudget();
        const bool atBoundary = impl_->stream.getPosition() == entry.byteOffset;
        if (atBoundary && !impl_->stream.lastError().empty()) {
            // Between entries, the compressed data itself is damaged or followed by garbage.
            failed_ = true;
            throw RawlogReadError(path_, entry.index, entry.byteOffset, impl_->stream.lastError());
        }
        if (atBoundary) {
            // A clean end between two entries - unless there was none: an empty file (or a
            // gzip that inflates to nothing) is no rawlog, however MRPT's tools take it.
            if (entry.index == 0) {
                throw fail(compressed_ ? "no entries: the compressed data is empty"
                                       : "no entries: the file is empty");
            }
            return std::nullopt;
        }
        throw fail("truncated: the file ends inside this entry");
    } catch (const std::bad_alloc&) {
        if (budget.exceeded()) throw overBudget();
        throw fail("corrupt entry (an impossible size made the reader run out of memory)");
    } catch (const std::exception& e) {
        if (budget.exceeded()) throw overBudget();
        throw fail(condensedMrptError(e.what()));
    }
    if (!entry.object) throw fail("null object stored as an entry");
    if (const std::string why = detail::damagedPart(*entry.object); !why.empty()) {
        throw fail("corrupt entry: " + why);
    }
    ++next_index_;
    return entry;
}

}  // namespace lodestone::io
