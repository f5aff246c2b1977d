#include <lodestone/inspect/RawlogSummary.h>
#include <lodestone/inspect/TimeText.h>
#include <lodestone/io/EntryContents.h>
#include <lodestone/io/RawlogReadError.h>
#include <lodestone/io/RawlogReader.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CSensoryFrame.h>

#include <iomanip>
#include <limits>

namespace lodestone::inspect {

namespace {
double seconds(mrpt::Clock::time_point a, mrpt::Clock::time_point b) {
    return mrpt::Clock::toDouble(b) - mrpt::Clock::toDouble(a);
}

void addObservation(SensorStats& s, const mrpt::obs::CObservation& obs) {
    ++s.count;
    ++s.classes[obs.GetRuntimeClass()->className];
    const auto t = obs.timestamp;
    if (t == INVALID_TIMESTAMP) return;
    ++s.timestamped;
    if (s.last) {
        const double step = seconds(*s.last, t);
        if (step < 0) ++s.backwards;
        s.largestGap = std::max(s.largestGap, step);
    }
    if (!s.first || t < *s.first) s.first = t;
    if (!s.last || t > *s.last) s.last = t;
}
}  // namespace

double SensorStats::span() const { return first && last ? seconds(*first, *last) : 0.0; }

double SensorStats::meanRate() const {
    const double s = span();
    if (s <= 0) return std::numeric_limits<double>::infinity();
    return static_cast<double>(timestamped - 1) / s;
}

RawlogSummaryBuilder::RawlogSummaryBuilder(std::string path, std::uint64_t fileBytes,
                                           bool compressed) {
    summary_.path = std::move(path);
    summary_.fileBytes = fileBytes;
    summary_.compressed = compressed;
}

void RawlogSummaryBuilder::add(const io::RawlogEntry& entry) {
    auto& summary = summary_;
    const bool isActions = IS_CLASS(*entry.object, mrpt::obs::CActionCollection);
    const bool unpaired = IS_CLASS(*entry.object, mrpt::obs::CSensoryFrame) && !previous_was_actions_;
    summary.unpairedActions += previous_was_actions_ && isActions;
    previous_was_actions_ = isActions;
    summary.unpairedFrames += unpaired;
    ++summary.entries;
    ++summary.entryClasses[entry.object->GetRuntimeClass()->className];
    summary.format = io::updateFormat(summary.format, *entry.object);
    if (const auto t = io::entryTimestamp(*entry.object)) {
        if (!summary.first || *t < *summary.first) summary.first = *t;
        if (!summary.last || *t > *summary.last) summary.last = *t;
    }
    for (const auto& obs : io::observationsOf(entry.object)) {
        ++summary.observationClasses[obs->GetRuntimeClass()->className];
        auto& sensor = summary.sensors[obs->sensorLabel];
        addObservation(sensor, *obs);
        sensor.inUnpairedFrames += unpaired;
        if (obs->timestamp != INVALID_TIMESTAMP) {
            if (!summary.first || obs->timestamp < *summary.first) summary.first = obs->timestamp;
            if (!summary.last || obs->timestamp > *summary.last) summary.last = obs->timestamp;
        }
    }
}

RawlogSummary RawlogSummaryBuilder::finish(std::optional<std::string> error,
                                           std::uint64_t uncompressedBytes) {
    summary_.error = std::move(error);
    summary_.unpairedActions += previous_was_actions_ && !summary_.error;
    summary_.uncompressedBytes = uncompressedBytes;
    return summary_;
}

RawlogSummary summarizeRawlog(const std::string& path) {
    io::RawlogReader reader(path);
    RawlogSummaryBuilder builder(path, reader.fileSize(), reader.isCompressed());
    std::optional<std::string> error;
    try {
        while (auto entry = reader.next()) builder.add(*entry);
    } catch (const io::RawlogReadError& e) {
        error = e.what();
    }
    return builder.finish(error, reader.bytesRead());
}

void printSummary(const RawlogSummary& s, std::ostream& out) {
    out << "File                : " << s.path << "\n";
    out << "Size on disk        : " << s.fileBytes << " bytes"
        << (s.compressed ? " (gzip, " + std::to_string(s.uncompressedBytes) + " uncompressed)"
                         : std::string(" (plain)"))
        << "\n";
    out << "Format              : " << io::toString(s.format) << "\n";
    out << "Entries             : " << s.entries << "\n";
    if (s.first && s.last) {
        out << "Earliest timestamp  : " << timeText(*s.first) << "\n";
        out << "Latest timestamp    : " << timeText(*s.last) << "\n";
        out << "Time span           : " << std::fixed << std::setprecision(3)
            << seconds(*s.first, *s.last) << " s\n";
    } else {
        out << "Timestamps          : none\n";
    }
    out << "Entry classes       :\n";
    for (const auto& [cls, n] : s.entryClasses)
        out << "  " << std::setw(8) << n << "  " << cls << "\n";
    out << "Observation classes :\n";
    for (const auto& [cls, n] : s.observationClasses) {
        out << "  " << std::setw(8) << n << "  " << cls << "\n";
    }
    out << "Sensors             :\n";
    out << "  " << std::left << std::setw(20) << "label" << std::setw(42) << "class" << std::right
        << std::setw(9) << "count" << std::setw(12) << "rate[Hz]" << std::setw(11) << "span[s]"
        << std::setw(13) << "max gap[s]" << std::setw(11) << "backwards"
        << "\n";
    for (const auto& [label, st] : s.sensors) {
        std::string classes;
        for (const auto& [cls, n] : st.classes) classes += (classes.empty() ? "" : ",") + cls;
        out << "  " << std::left << std::setw(20) << (label.empty() ? "(no label)" : label)
            << std::setw(42) << classes << std::right << std::setw(9) << st.count << std::fixed
            << std::setprecision(3) << std::setw(12) << st.meanRate() << std::setw(11) << st.span()
            << std::setw(13) << st.largestGap << std::setw(11) << st.backwards << "\n";
    }
    if (s.unpairedFrames > 0 || s.unpairedActions > 0) {
        out << "Note                : " << s.unpairedFrames
            << " sensory frame(s) without an action collection before them and "
            << s.unpairedActions
            << " action collection(s) without a sensory frame after them; MRPT's "
               "action/observation pair reader (and so rawlog-edit --info) skips these\n";
    }
    if (s.error) out << "READ ERROR          : " << *s.error << "\n";
}

}  // namespace lodestone::inspect
