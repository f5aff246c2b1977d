#pragma once

#include <mrpt/obs/CObservation.h>

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace lodestone::inspect::report {

/** A camera frame shown small in the report. */
struct Thumbnail {
    double time{0};     ///< [s since the rawlog's first timestamp]
    std::string label;  ///< sensor label
    std::string rgb, depth;  ///< files relative to the report folder; empty: none in the frame
    std::string why;    ///< "every N s", "before a gap", "after a gap"
};

struct ThumbnailOptions {
    double every{10.0};   ///< [s] between regular thumbnails of a camera
    int width{240};       ///< [px]
    double depthMax{6.0}; ///< [m] the depth colour scale's top (viridis from 0; no depth: black)
    std::size_t maxPerCamera{400};
    std::size_t maxGapFramesPerCamera{100};
};

/** Picks camera frames (RGB-D scans and plain images) every `every` seconds and on both sides
 * of each gap, and writes them small (JPEG colour, PNG colour-mapped depth) into a folder as
 * they stream past: only the frame before the current one is held. */
class ThumbnailSampler {
  public:
    ThumbnailSampler(std::filesystem::path reportDir, std::string subdir,
                     ThumbnailOptions options = {});

    /** `afterGap`: the step from the camera's previous frame to this one is a gap. */
    void add(const mrpt::obs::CObservation::Ptr& obs, double time, bool afterGap);

    const std::vector<Thumbnail>& thumbnails() const { return thumbnails_; }
    /** Frames picked whose images could not be loaded (a missing external file). */
    std::size_t unreadable() const { return unreadable_; }

    static bool isCamera(const mrpt::obs::CObservation& obs);

  private:
    struct Camera {
        double next{0};
        std::size_t taken{0}, gapFrames{0};
        mrpt::obs::CObservation::Ptr previous;
        double previousTime{0};
        bool previousTaken{false};
    };
    bool take(const mrpt::obs::CObservation& obs, double time, const std::string& why);

    std::filesystem::path dir_;
    std::string subdir_;
    ThumbnailOptions options_;
    std::map<std::string, Camera> cameras_;
    std::vector<Thumbnail> thumbnails_;
    std::size_t unreadable_{0};
};

}  // namespace lodestone::inspect::report
