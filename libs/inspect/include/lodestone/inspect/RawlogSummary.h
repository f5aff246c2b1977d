#pragma once

#include <lodestone/io/RawlogFormat.h>
#include <lodestone/io/RawlogReader.h>
#include <mrpt/core/Clock.h>

#include <cstdint>
#include <map>
#include <optional>
#include <ostream>
#include <string>

namespace lodestone::inspect {

/** What one sensor label contributed to a rawlog. */
struct SensorStats {
    std::map<std::string, std::size_t> classes;  ///< class name -> observations
    std::size_t count{0};
    std::size_t timestamped{0};  ///< observations with a valid timestamp
    std::optional<mrpt::Clock::time_point> first, last;
    double largestGap{0};      ///< largest step between consecutive observations [s]
    std::size_t backwards{0};  ///< observations older than the one before them
    /** Observations in sensory frames not preceded by an action collection. MRPT's
     * action/observation pair reader, and so `rawlog-edit --info`, skips them. */
    std::size_t inUnpairedFrames{0};

    double span() const;  ///< last - first [s]
    /** (count - 1) / span [Hz], as rawlog-edit --info computes it; inf for a zero span. */
    double meanRate() const;
};

/** The facts `lodestone-inspect summary` prints, gathered in one streaming pass. */
struct RawlogSummary {
    std::string path;
    std::uint64_t fileBytes{0}, uncompressedBytes{0};
    bool compressed{false};
    io::RawlogFormat format{io::RawlogFormat::Empty};
    std::size_t entries{0};                                 ///< top-level objects
    std::map<std::string, std::size_t> entryClasses;        ///< top-level class -> count
    std::map<std::string, std::size_t> observationClasses;  ///< observation class -> count
    std::optional<mrpt::Clock::time_point> first, last;
    std::size_t unpairedFrames{0};   ///< CSensoryFrame entries not preceded by actions
    std::size_t unpairedActions{0};  ///< CActionCollection entries not followed by a frame
    std::map<std::string, SensorStats> sensors;  ///< by sensor label
    std::optional<std::string> error;            ///< why reading stopped early, if it did
};

/** Gathers a summary entry by entry, for a pass over the rawlog that does more than summarize
 * (the report). */
class RawlogSummaryBuilder {
  public:
    RawlogSummaryBuilder(std::string path, std::uint64_t fileBytes, bool compressed);
    void add(const io::RawlogEntry& entry);
    /** The summary; `error`: why reading stopped early, if it did. */
    RawlogSummary finish(std::optional<std::string> error, std::uint64_t uncompressedBytes);

  private:
    RawlogSummary summary_;
    bool previous_was_actions_{false};
};

/** Reads `path` once (flat memory) and gathers its summary. A corrupt file yields the
 * summary up to the fault, with `error` set. Throws only if the file cannot be opened. */
RawlogSummary summarizeRawlog(const std::string& path);

void printSummary(const RawlogSummary& summary, std::ostream& out);

}  // namespace lodestone::inspect
