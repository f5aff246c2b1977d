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

/** Writes a TUM trajectory line by line (flushed, so a crash keeps what was written) to
 * `path.partial`, renamed to `path` by close() or the destructor at the normal end of a scope,
 * not when an exception unwinds past it (as RawlogWriter). */
class TumTrajectoryWriter {
  public:
    /** Creates `path.partial` with a comment header; throws std::runtime_error naming it on
     * failure. */
    explicit TumTrajectoryWriter(const std::string& path);
    ~TumTrajectoryWriter();
    TumTrajectoryWriter(const TumTrajectoryWriter&) = delete;
    TumTrajectoryWriter& operator=(const TumTrajectoryWriter&) = delete;
    void write(double timestamp, const mrpt::poses::CPose3D& pose);
    /** Finishes the file and renames it to path(); throws std::runtime_error on an error. */
    void close();
    const std::string& path() const { return path_; }

  private:
    std::string path_;
    std::ofstream out_;
    int uncaught_at_start_{0};
};

/** Reads a TUM trajectory; '#' lines are comments. Throws std::runtime_error naming the file
 * and line for a malformed line. */
std::vector<TumPose> readTumTrajectory(const std::string& path);

/** The pose of `trajectory` (sorted by time) nearest `t`, if one lies within `maxDt`; else
 * nullptr. */
const TumPose* poseNearest(const std::vector<TumPose>& trajectory, double t, double maxDt);

}  // namespace lodestone::io
