#pragma once

#include <lodestone/io/RawlogWriter.h>
#include <mrpt/serialization/CSerializable.h>

#include <cstdint>
#include <functional>
#include <map>
#include <queue>
#include <string>
#include <vector>

namespace lodestone::grab {

/** Writes observations from several sensors in time order through a flushed RawlogWriter: an
 * observation waits until one `window` seconds newer has arrived (sensors deliver in bursts,
 * each in its own order), then goes to disk at once. A killed grab loses what the window held.
 * One that arrives older than what was already written (later than the window allows) is
 * written anyway, out of order, and counted. */
class ReorderingWriter {
  public:
    ReorderingWriter(const std::string& path, int gzipLevel, double window);

    /** Called with every object just written, and the newest time added so far [s]. */
    void onWritten(std::function<void(const mrpt::serialization::CSerializable::Ptr&, double)> f) {
        on_written_ = std::move(f);
    }

    void add(mrpt::serialization::CSerializable::Ptr object);
    void writeDue();  ///< everything older than the newest time minus the window
    void drain();     ///< everything
    void close();     ///< drain, then finish the file (renamed from .partial)

    std::size_t written() const { return writer_.entriesWritten(); }
    std::size_t late() const { return late_; }
    std::size_t waiting() const { return heap_.size(); }
    const std::map<std::string, std::size_t>& writtenByLabel() const { return by_label_; }
    /** Size of the file so far [bytes]. */
    std::uint64_t bytesOnDisk() const;
    const std::string& path() const { return writer_.path(); }

  private:
    struct Item {
        double time;
        std::uint64_t order;  // arrival: equal times keep it
        mrpt::serialization::CSerializable::Ptr object;
        bool operator>(const Item& o) const {
            return time != o.time ? time > o.time : order > o.order;
        }
    };
    void write(const Item& item);

    io::RawlogWriter writer_;
    double window_;
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> heap_;
    std::uint64_t arrivals_{0};
    double newest_{-1e300}, last_written_{-1e300};
    std::size_t late_{0};
    std::map<std::string, std::size_t> by_label_;
    std::function<void(const mrpt::serialization::CSerializable::Ptr&, double)> on_written_;
};

}  // namespace lodestone::grab
