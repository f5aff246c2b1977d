#pragma once

#include <lodestone/inspect/report/TimeBins.h>
#include <mrpt/obs/CObservation.h>

#include <array>
#include <map>
#include <string>
#include <vector>

namespace lodestone::inspect::report {

/** Something that happened at a time: a gap (from `time`, lasting `size` s) or a backwards
 * timestamp (at `time`, `size` s older than the newest before it). */
struct TimeEvent {
    double time{0};
    double size{0};
};

/** One sensor label over time, as the report draws and tabulates it. Times are seconds since
 * the rawlog's first timestamp. */
struct SensorTimeline {
    std::string label;
    std::string className;  ///< of its first observation
    std::size_t count{0};
    TimeBins<CountBin> density;
    double medianStep{0};  ///< [s]; 0 when it has fewer than two samples
    bool eventDriven{false};  ///< emits on change (wheel drops): no gaps, `events` instead
    std::vector<TimeEvent> gaps;       ///< steps longer than gapFactor x medianStep
    std::vector<TimeEvent> backwards;  ///< timestamps older than the newest before them
    std::size_t gapCount{0}, backwardCount{0};  ///< all of them (the lists are capped)
    double largestGap{0}, largestBackwards{0};
    std::vector<std::pair<double, bool>> wheelDrops;  ///< time, lifted (either wheel down)
};

/** Builds every sensor's timeline from observations in file order. A gap is a step longer than
 * `gapFactor` times the sensor's median step - four or more samples of a periodic sensor
 * missing in a row at the default 5 - whatever its rate, so no threshold per sensor is set. */
class TimelineBuilder {
  public:
    explicit TimelineBuilder(double gapFactor = 5.0);
    /** `time`: seconds since the rawlog's first timestamp. */
    void add(const mrpt::obs::CObservation& obs, double time);
    std::vector<SensorTimeline> finish();  ///< by label
    /** Whether an observation of `label` at `time` would follow a gap, judged by the median
     * step so far (false until the sensor has a few steps): for acting while streaming. */
    bool wouldBeGap(const std::string& label, double time) const;

    static constexpr std::size_t kMaxListed = 2000;  ///< gaps / backwards kept per sensor

  private:
    /** Steps in octave eighths from 2^-20 s to 2^12 s: the median to 9 % in 256 counters. */
    struct StepHistogram {
        static constexpr int kPerOctave = 8, kLowOctave = -20, kBins = 32 * kPerOctave;
        std::array<std::size_t, kBins> counts{};
        std::size_t total{0};
        void add(double step);
        double median() const;
    };
    struct State {
        SensorTimeline timeline;
        double newest{-1e300};
        bool any{false};
        StepHistogram steps;
        std::vector<TimeEvent> candidates;  // steps long enough that they may be gaps
    };
    double gap_factor_;
    std::map<std::string, State> sensors_;
};

}  // namespace lodestone::inspect::report
