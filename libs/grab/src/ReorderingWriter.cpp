#include <lodestone/grab/ReorderingWriter.h>
#include <lodestone/io/EntryContents.h>
#include <lodestone/io/RawlogPaths.h>
#include <mrpt/obs/CObservation.h>

#include <filesystem>

namespace lodestone::grab {

ReorderingWriter::ReorderingWriter(const std::string& path, int gzipLevel, double window)
    : writer_(path, io::RawlogWriter::Options{gzipLevel}), window_(window) {}

void ReorderingWriter::add(mrpt::serialization::CSerializable::Ptr object) {
    if (!object) return;
    const auto t = io::entryTimestamp(*object);
    if (!t) {  // nothing to order it by: now
        write({last_written_, arrivals_++, std::move(object)});
        return;
    }
    const double time = mrpt::Clock::toDouble(*t);
    newest_ = std::max(newest_, time);
    heap_.push({time, arrivals_++, std::move(object)});
}

void ReorderingWriter::write(const Item& item) {
    if (item.time < last_written_) ++late_;
    last_written_ = std::max(last_written_, item.time);
    writer_.write(*item.object);
    if (const auto* obs = dynamic_cast<const mrpt::obs::CObservation*>(item.object.get())) {
        ++by_label_[obs->sensorLabel];
    } else {
        ++by_label_[item.object->GetRuntimeClass()->className];
    }
    if (on_written_) on_written_(item.object, newest_);
}

void ReorderingWriter::writeDue() {
    while (!heap_.empty() && heap_.top().time <= newest_ - window_) {
        write(heap_.top());
        heap_.pop();
    }
}

void ReorderingWriter::drain() {
    while (!heap_.empty()) {
        write(heap_.top());
        heap_.pop();
    }
}

void ReorderingWriter::close() {
    drain();
    writer_.close();
}

std::uint64_t ReorderingWriter::bytesOnDisk() const {
    std::error_code ec;
    for (const auto& p : {io::partialPath(writer_.path()), writer_.path()}) {
        const auto size = std::filesystem::file_size(p, ec);
        if (!ec) return size;
    }
    return 0;
}

}  // namespace lodestone::grab
