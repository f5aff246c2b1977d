#include <lodestone/drivers/registerDrivers.h>
#include <lodestone/grab/GrabConfig.h>
#include <lodestone/grab/GrabSession.h>
#include <lodestone/grab/LiveSlamFeed.h>
#include <lodestone/grab/ReorderingWriter.h>
#include <lodestone/grab/SensorRunner.h>
#include <lodestone/io/RawlogPaths.h>
#include <lodestone/obs/registerAllClasses.h>
#include <lodestone/slamapp/SlamRun.h>
#include <mrpt/img/CImage.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <memory>
#include <sstream>
#include <thread>

namespace lodestone::grab {

namespace {
using Clock = std::chrono::steady_clock;

double since(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

// "grab 12.0 s | SIM 280.0/s 3360 | 5.2 MB written": per sensor section the rate over the last
// period and the count, then the file.
class StatusLine {
  public:
    StatusLine(std::ostream& err, bool terminal, bool quiet) : err_(err), terminal_(terminal), quiet_(quiet) {}
    std::atomic<std::size_t> slamNodes{0}, slamClosures{0};  // set from the SLAM thread

    void print(double elapsed, const std::vector<std::unique_ptr<SensorRunner>>& runners,
               const ReorderingWriter& writer, const LiveSlamFeed* feed) {
        if (quiet_) return;
        std::string line;
        char buf[160];
        std::snprintf(buf, sizeof buf, "grab %7.1f s", elapsed);
        line += buf;
        counts_.resize(runners.size(), 0);
        for (std::size_t i = 0; i < runners.size(); ++i) {
            const auto& r = *runners[i];
            const std::size_t n = r.produced();
            const double rate = elapsed > last_ ? (n - counts_[i]) / (elapsed - last_) : 0.0;
            counts_[i] = n;
            std::snprintf(buf, sizeof buf, " | %s %.1f/s %zu%s", r.section().c_str(), rate, n,
                          r.state() == SensorRunner::State::Running ? "" : (std::string(" ") + toString(r.state())).c_str());
            line += buf;
        }
        std::snprintf(buf, sizeof buf, " | %.1f MB written, %zu waiting", writer.bytesOnDisk() / 1e6,
                      writer.waiting());
        line += buf;
        if (feed) {
            const auto f = feed->current();
            std::snprintf(buf, sizeof buf, " | slam %zu nodes, %zu closures, lag %.2f s, %zu frames skipped",
                          slamNodes.load(), slamClosures.load(), f.lagNow, f.skippedFrames);
            line += buf;
        }
        last_ = elapsed;
        err_ << (terminal_ ? "\r" : "") << line << (terminal_ ? "" : "\n") << std::flush;
        drawn_ = true;
    }
    void end() {
        if (drawn_ && terminal_ && !quiet_) err_ << "\n";
    }

  private:
    std::ostream& err_;
    bool terminal_, quiet_, drawn_{false};
    double last_{0};
    std::vector<std::size_t> counts_;
};
// The reorder window: as set, or twice the slowest sensor's period (a sensor delivers what it
// grabbed at its next doProcess), at least 50 ms.
double reorderWindow(const GrabConfig& config) {
    if (config.reorderWindow >= 0) return config.reorderWindow;
    double window = 0.05;
    for (const auto& s : config.sensors) window = std::max(window, 2.0 / s.processRate);
    return std::min(window, 0.9);
}

/** Live SLAM: lodestone-slam's run on a thread of its own, reading what the writer writes.
 * Whatever happens (a write error throws), the thread is ended and joined. */
class LiveSlam {
  public:
    LiveSlam(const GrabOptions& options, const std::string& prefix, const std::string& imagesDir,
             ReorderingWriter& writer, StatusLine& status)
        : feed_(std::make_shared<LiveSlamFeed>(options.maxLag)) {
        // Colour images go to the images folder as they are grabbed; SLAM reads them there.
        mrpt::img::CImage::setImagesPathBase(imagesDir);
        auto feed = feed_;
        writer.onWritten([feed](const mrpt::serialization::CSerializable::Ptr& o, double newest) {
            if (auto obs = std::dynamic_pointer_cast<mrpt::obs::CObservation>(o)) feed->push(obs, newest);
        });
        slamapp::SlamRunOptions so;
        so.live = feed_;
        so.config = options.slamConfig;
        so.outDir = options.slamOut.empty() ? prefix + "_slam" : options.slamOut;
        so.mapIn = options.slamMapIn;
        so.decodeAhead = 0;  // the observations arrive decoded
        so.quiet = true;
        so.view = options.slamView;  // (closes with the grab)
        so.mesh = options.slamMesh;
        so.onProgress = [&status](std::size_t nodes, std::size_t closures) {
            status.slamNodes = nodes;
            status.slamClosures = closures;
        };
        thread_ = std::thread([this, so, feed] {
            result_ = slamapp::runSlam(so, out_, err_);
            feed->abandon();  // if the run ended early, the grab must not queue for it
        });
    }
    ~LiveSlam() { join(); }
    LiveSlam(const LiveSlam&) = delete;
    LiveSlam& operator=(const LiveSlam&) = delete;

    const LiveSlamFeed* feed() const { return feed_.get(); }

    /** Closes the feed and waits: the run drains it, optimizes and writes its outputs. Then its
     * figures go into `result`. */
    void finish(GrabResult& result) {
        join();
        const auto f = feed_->stats();
        result.slam = true;
        result.slamExitCode = result_.exitCode;
        result.slamNodes = result_.nodes;
        result.slamClosures = result_.loopClosures;
        result.skippedFrames = f.skippedFrames;
        result.frames = f.frames;
        result.lagP50 = f.lagP50;
        result.lagP99 = f.lagP99;
        result.lagMax = f.lagMax;
    }
    std::string output() const { return out_.str(); }
    std::string errors() const { return err_.str(); }

  private:
    void join() {
        feed_->close();
        if (thread_.joinable()) thread_.join();
    }
    std::shared_ptr<LiveSlamFeed> feed_;
    std::thread thread_;
    slamapp::SlamRunResult result_;
    std::ostringstream out_, err_;
};

/** Writes what the sensors queue until a signal, the duration or every sensor finished; says
 * which ended it. A sensor that dies is reported once, with its section; the others go on. */
std::string grabUntilStopped(const GrabConfig& config, const GrabOptions& options,
                             const std::atomic<bool>& stop, ObservationQueue& queue,
                             const std::vector<std::unique_ptr<SensorRunner>>& runners,
                             ReorderingWriter& writer, StatusLine& status, const LiveSlamFeed* feed,
                             Clock::time_point t0, std::ostream& err) {
    double nextStatus = config.statusPeriod;
    std::vector<bool> reported(runners.size(), false);
    while (true) {
        for (auto& o : queue.takeAll(std::chrono::milliseconds(50))) writer.add(std::move(o));
        writer.writeDue();
        const double elapsed = since(t0);
        bool anyRunning = false;
        for (std::size_t i = 0; i < runners.size(); ++i) {
            const auto state = runners[i]->state();
            anyRunning |= state == SensorRunner::State::Running;
            if (state == SensorRunner::State::Died && !reported[i]) {
                reported[i] = true;
                status.end();
                err << "lodestone-grab: sensor section '" << runners[i]->section()
                    << "' died while grabbing: " << runners[i]->error() << " (the others go on)\n";
            }
        }
        if (elapsed >= nextStatus) {
            status.print(elapsed, runners, writer, feed);
            nextStatus += config.statusPeriod;
        }
        if (stop.load()) return "signal";
        if (elapsed >= options.duration) return "duration";
        if (!anyRunning) return "sensors finished";
    }
}

/** The summary lines of a finished grab. */
void printSummary(const GrabResult& result, const LiveSlam* slam, std::ostream& out,
                  std::ostream& err) {
    out << "lodestone-grab: " << result.written << " observations in " << result.seconds
        << " s -> " << result.rawlog << " (stopped by " << result.stoppedBy << ")\n";
    for (const auto& s : result.sensors) {
        out << "  " << s.section << " (" << s.driver << "): " << s.produced << " observations, "
            << s.state << (s.error.empty() ? "" : ": " + s.error) << "\n";
    }
    if (result.slam) {
        char line[256];
        std::snprintf(line, sizeof line,
                      "  live SLAM: %zu nodes, %zu loop closures; lag behind the newest "
                      "observation p50 %.3f s, p99 %.3f s, max %.3f s; %zu of %zu RGB-D frames "
                      "skipped\n",
                      result.slamNodes, result.slamClosures, result.lagP50, result.lagP99,
                      result.lagMax, result.skippedFrames, result.frames);
        out << line << slam->output();
        err << slam->errors();
    }
    if (result.late) {
        out << "  " << result.late << " observation(s) arrived later than reorder_window and were "
            << "written out of time order\n";
    }
}

}  // namespace

GrabResult runGrab(const GrabOptions& options, const std::atomic<bool>& stop, std::ostream& out,
                   std::ostream& err) {
    lodestone::registerAllClasses();
    drivers::registerDrivers();
    const GrabConfig config = readGrabConfig(options.config);
    if (!options.slamConfig.empty())  // before any work
        slamapp::checkSlamConfig(options.slamConfig, options.slamMapIn);
    GrabResult result;
    const std::string prefix = !options.out.empty() ? options.out
                               : !config.rawlogPrefix.empty() ? config.rawlogPrefix
                                                              : std::string("grab");
    result.rawlog = prefix + ".rawlog.gz";
    io::prepareOutputFile(result.rawlog);
    const std::string imagesDir = prefix + "_Images";

    // Every sensor starts, or none: an error names the section before anything is written.
    ObservationQueue queue;
    std::vector<std::unique_ptr<SensorRunner>> runners;
    for (const auto& s : config.sensors) {
        try {
            runners.push_back(std::make_unique<SensorRunner>(s, *config.ini, imagesDir, queue));
        } catch (const std::exception& e) {
            err << "lodestone-grab: error: " << config.path << ": " << e.what() << "\n";
            result.exitCode = 1;
            return result;
        }
    }
    ReorderingWriter writer(result.rawlog, config.gzipLevel, reorderWindow(config));
    StatusLine status(err, options.terminal, options.quiet);
    std::unique_ptr<LiveSlam> slam;
    if (!options.slamConfig.empty()) {
        slam = std::make_unique<LiveSlam>(options, prefix, imagesDir, writer, status);
    }
    const LiveSlamFeed* feed = slam ? slam->feed() : nullptr;
    const auto t0 = Clock::now();
    for (auto& r : runners) r->start();
    result.stoppedBy =
        grabUntilStopped(config, options, stop, queue, runners, writer, status, feed, t0, err);
    for (auto& r : runners) r->stop();  // joined: each queued what it had
    for (auto& o : queue.takeAll(std::chrono::milliseconds(0))) writer.add(std::move(o));
    writer.close();
    result.seconds = since(t0);
    status.print(result.seconds, runners, writer, feed);
    status.end();
    if (slam) slam->finish(result);

    result.written = writer.written();
    result.late = writer.late();
    for (std::size_t i = 0; i < runners.size(); ++i) {
        const auto& r = *runners[i];
        result.sensors.push_back({r.section(), config.sensors[i].driver, toString(r.state()), r.error(), r.produced()});
        if (r.state() == SensorRunner::State::Died) result.exitCode = 1;
    }
    printSummary(result, slam.get(), out, err);
    if (result.slam && result.slamExitCode != 0) result.exitCode = 1;
    return result;
}

}  // namespace lodestone::grab
