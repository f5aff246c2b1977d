#pragma once

#include <mrpt/poses/CPose3D.h>

#include <fstream>
#include <string>
#include <vector>

namespace lodestone::io {

/** One line of a TUM RGB-D trajectory: "timestamp tx ty tz qx qy qz qw". */
struct TumPose {
    double timestamp{0};  ///< [s]
    mrpt::poses::CPose3D pose;
};

/** Writes a TUM trajectory line by line (flushed, so a crash keeps what was written). */
class TumTrajectoryWriter {
  public:
    /** Creates `path` with a comment header; throws std::runtime_error naming it on failure. */
    explicit TumTrajectoryWriter(const std::string& path);
    void write(double timestamp, const mrpt::poses::CPose3D& pose);
    const std::string& path() const { return path_; }

  private:
    std::string path_;
    std::ofstream out_;
};

/** Reads a TUM trajectory; '#' lines are comments. Throws std::runtime_error naming the file
 * and line for a malformed line. */
std::vector<TumPose> readTumTrajectory(const std::string& path);

}  // namespace lodestone::io
