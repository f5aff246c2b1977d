#pragma once

#include <mrpt/obs/CObservation.h>

#include <string>

namespace lodestone::io {

/** A stream of observations in time order: a rawlog file, live sensors or the simulator.
 * Everything downstream (odometry, SLAM, inspection) reads through this one interface. */
class DataSource {
  public:
    virtual ~DataSource() = default;

    /** The next observation, or nullptr when the source is exhausted. Throws (with the
     * source's name and position) when the input is corrupt; observations before the fault
     * have all been returned by then. */
    virtual mrpt::obs::CObservation::Ptr next() = 0;

    /** Human-readable name of the source, used in messages (e.g. the file path). */
    virtual std::string name() const = 0;
};

}  // namespace lodestone::io
