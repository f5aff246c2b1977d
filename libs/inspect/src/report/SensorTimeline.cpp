#include <lodestone/inspect/report/SensorTimeline.h>
#include <lodestone/obs/CObservationWheelDrop.h>

#include <cmath>

namespace lodestone::inspect::report {

namespace {
// Below this many steps the median is not yet known: every positive step is a candidate gap.
constexpr std::size_t kStepsForMedian = 16;
// Candidates are steps above this multiple of the running median; the final test uses the
// median of all steps, so the margin keeps what a later, lower median would call a gap.
constexpr double kCandidateFactor = 2.0;
constexpr std::size_t kMaxCandidates = 20000;
}  // namespace

void TimelineBuilder::StepHistogram::add(double step) {
    if (!(step > 0)) return;
    const int bin = static_cast<int>(std::floor((std::log2(step) - kLowOctave) * kPerOctave));
    ++counts[static_cast<std::size_t>(std::clamp(bin, 0, kBins - 1))];
    ++total;
}

double TimelineBuilder::StepHistogram::median() const {
    if (total == 0) return 0;
    std::size_t seen = 0;
    for (int i = 0; i < kBins; ++i) {
        seen += counts[static_cast<std::size_t>(i)];
        if (2 * seen >= total) return std::exp2(kLowOctave + (i + 0.5) / kPerOctave);
    }
    return 0;
}

TimelineBuilder::TimelineBuilder(double gapFactor) : gap_factor_(gapFactor) {}

void TimelineBuilder::add(const mrpt::obs::CObservation& obs, double time) {
    auto& s = sensors_[obs.sensorLabel];
    auto& tl = s.timeline;
    if (tl.count == 0) {
        tl.label = obs.sensorLabel;
        tl.className = obs.GetRuntimeClass()->className;
    }
    ++tl.count;
    if (!std::isfinite(time)) return;  // no timestamp: counted, not placed
    tl.density.at(time).count++;
    if (const auto* drop = dynamic_cast<const obs::CObservationWheelDrop*>(&obs)) {
        tl.eventDriven = true;
        if (tl.wheelDrops.size() < kMaxListed) tl.wheelDrops.emplace_back(time, drop->lifted());
    }
    if (s.any) {
        const double step = time - s.newest;
        if (step < 0) {
            ++tl.backwardCount;
            tl.largestBackwards = std::max(tl.largestBackwards, -step);
            if (tl.backwards.size() < kMaxListed) tl.backwards.push_back({time, -step});
        } else {
            s.steps.add(step);
            const bool early = s.steps.total < kStepsForMedian;
            if (step > 0 && (early || step > kCandidateFactor * s.steps.median()) &&
                s.candidates.size() < kMaxCandidates) {
                s.candidates.push_back({s.newest, step});
            }
        }
    }
    s.any = true;
    s.newest = std::max(s.newest, time);
}

bool TimelineBuilder::wouldBeGap(const std::string& label, double time) const {
    const auto it = sensors_.find(label);
    if (it == sensors_.end() || !it->second.any || !std::isfinite(time)) return false;
    const auto& s = it->second;
    if (s.timeline.eventDriven || s.steps.total < kStepsForMedian) return false;
    return time - s.newest > gap_factor_ * s.steps.median();
}

std::vector<SensorTimeline> TimelineBuilder::finish() {
    std::vector<SensorTimeline> out;
    for (auto& [label, s] : sensors_) {
        auto& tl = s.timeline;
        tl.medianStep = s.steps.median();
        if (!tl.eventDriven && tl.medianStep > 0) {
            for (const auto& c : s.candidates) {
                if (c.size <= gap_factor_ * tl.medianStep) continue;
                ++tl.gapCount;
                tl.largestGap = std::max(tl.largestGap, c.size);
                if (tl.gaps.size() < kMaxListed) tl.gaps.push_back(c);
            }
        }
        out.push_back(std::move(tl));
    }
    return out;
}

}  // namespace lodestone::inspect::report
