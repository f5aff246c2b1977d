#pragma once

#include <lodestone/io/DataSource.h>

#include <atomic>
#include <condition_variable>
#include <deque>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <thread>

namespace lodestone::io {

/** Reads and decodes ahead on a second thread: a worker takes observations from another source,
 * loads their external data and decodes their delay-loaded images (CObservation::load(), and
 * the colour PNG / JPEG files, which MRPT decodes only when their pixels are first touched) and
 * queues them, at most `depth` ahead of the caller; next() hands them over in the
 * inner source's order. What comes out is exactly what the inner source gives, decoded, so
 * results do not depend on it (and are deterministic: one producer, one consumer, one order).
 *
 * - A fault of the inner source is handed over after every observation before it, as the inner
 *   source itself does. An image that fails to load is left unloaded: the consumer's own load()
 *   meets the same error where it would have without prefetching.
 * - Memory: at most `depth` decoded observations besides the one the caller holds.
 * - The inner source is only touched from the worker; `progress` (e.g. a rawlog's fraction
 *   read) is sampled there after each observation and read back with progress(). */
class PrefetchingSource : public DataSource {
  public:
    PrefetchingSource(std::unique_ptr<DataSource> inner, std::size_t depth,
                      std::function<double()> progress = {});
    ~PrefetchingSource() override;
    PrefetchingSource(const PrefetchingSource&) = delete;
    PrefetchingSource& operator=(const PrefetchingSource&) = delete;

    mrpt::obs::CObservation::Ptr next() override;
    std::string name() const override { return name_; }
    double progress() const { return progress_.load(); }

  private:
    void run();

    std::unique_ptr<DataSource> inner_;
    const std::string name_;
    const std::size_t depth_;
    std::function<double()> progressOf_;
    std::atomic<double> progress_{0};
    std::mutex mutex_;
    std::condition_variable notEmpty_, notFull_;
    std::deque<mrpt::obs::CObservation::Ptr> queue_;
    bool done_{false}, stop_{false};
    std::exception_ptr error_;
    std::thread worker_;  // last: starts once everything above exists
};

}  // namespace lodestone::io
