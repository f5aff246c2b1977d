#include <lodestone/inspect/report/Thumbnails.h>
#include <lodestone/plot/Colormap.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/obs/CObservationImage.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <cmath>
#include <cstdio>

namespace lodestone::inspect::report {

namespace fs = std::filesystem;

namespace {
cv::Mat resizedToWidth(const cv::Mat& in, int width) {
    if (in.empty() || in.cols <= width) return in.clone();
    cv::Mat out;
    const int height = std::max(1, static_cast<int>(std::lround(in.rows * double(width) / in.cols)));
    cv::resize(in, out, cv::Size(width, height), 0, 0, cv::INTER_AREA);
    return out;
}

cv::Mat colourImage(const mrpt::img::CImage& image) {
    cv::Mat m = image.asCvMat<cv::Mat>(mrpt::img::SHALLOW_COPY);
    if (m.channels() == 1) {
        cv::Mat bgr;
        cv::cvtColor(m, bgr, cv::COLOR_GRAY2BGR);
        return bgr;
    }
    return m;
}

cv::Mat3b colourDepth(const mrpt::obs::CObservation3DRangeScan& scan, int width, double depthMax) {
    const plot::Colormap colours(0.0, depthMax);
    const int rows = static_cast<int>(scan.rangeImage.rows());
    const int cols = static_cast<int>(scan.rangeImage.cols());
    // Subsample while colouring: the thumbnail is a few hundred pixels wide.
    const int step = std::max(1, cols / std::max(width, 1));
    cv::Mat3b out((rows + step - 1) / step, (cols + step - 1) / step, cv::Vec3b(0, 0, 0));
    for (int r = 0; r < rows; r += step) {
        for (int c = 0; c < cols; c += step) {
            const auto raw = scan.rangeImage(r, c);
            if (raw == 0) continue;
            out(r / step, c / step) = colours(raw * scan.rangeUnits);
        }
    }
    return out;
}

std::string fileName(const std::string& label, std::size_t n, const char* kind, const char* ext) {
    std::string safe;
    for (const char ch : label) safe += std::isalnum(static_cast<unsigned char>(ch)) ? ch : '_';
    char buf[96];
    std::snprintf(buf, sizeof buf, "%s_%05zu_%s.%s", safe.c_str(), n, kind, ext);
    return buf;
}
}  // namespace

ThumbnailSampler::ThumbnailSampler(fs::path reportDir, std::string subdir, ThumbnailOptions options)
    : dir_(std::move(reportDir)), subdir_(std::move(subdir)), options_(options) {}

bool ThumbnailSampler::isCamera(const mrpt::obs::CObservation& obs) {
    return IS_CLASS(obs, mrpt::obs::CObservation3DRangeScan) || IS_CLASS(obs, mrpt::obs::CObservationImage);
}

bool ThumbnailSampler::take(const mrpt::obs::CObservation& obs, double time, const std::string& why) {
    auto& camera = cameras_[obs.sensorLabel];
    if (camera.taken >= options_.maxPerCamera) return false;
    Thumbnail t{time, obs.sensorLabel, "", "", why};
    const std::size_t n = thumbnails_.size();
    const fs::path folder = dir_ / subdir_;
    fs::create_directories(folder);
    try {
        obs.load();  // delay-loaded images live in the rawlog's external images folder
        if (const auto* scan = dynamic_cast<const mrpt::obs::CObservation3DRangeScan*>(&obs)) {
            if (scan->hasIntensityImage && !scan->intensityImage.isEmpty()) {
                t.rgb = subdir_ + "/" + fileName(obs.sensorLabel, n, "rgb", "jpg");
                cv::imwrite((dir_ / t.rgb).string(),
                            resizedToWidth(colourImage(scan->intensityImage), options_.width),
                            {cv::IMWRITE_JPEG_QUALITY, 85});
            }
            if (scan->hasRangeImage && scan->rangeImage.rows() > 0) {
                t.depth = subdir_ + "/" + fileName(obs.sensorLabel, n, "depth", "png");
                cv::imwrite((dir_ / t.depth).string(),
                            resizedToWidth(colourDepth(*scan, options_.width, options_.depthMax),
                                           options_.width));
            }
        } else if (const auto* image = dynamic_cast<const mrpt::obs::CObservationImage*>(&obs)) {
            t.rgb = subdir_ + "/" + fileName(obs.sensorLabel, n, "rgb", "jpg");
            cv::imwrite((dir_ / t.rgb).string(),
                        resizedToWidth(colourImage(image->image), options_.width),
                        {cv::IMWRITE_JPEG_QUALITY, 85});
        }
        obs.unload();
    } catch (const std::exception&) {
        ++unreadable_;  // the frame is there, its pixels are not: the report says how many
        obs.unload();
        return false;
    }
    if (t.rgb.empty() && t.depth.empty()) return false;
    ++camera.taken;
    thumbnails_.push_back(std::move(t));
    return true;
}

void ThumbnailSampler::add(const mrpt::obs::CObservation::Ptr& obs, double time, bool afterGap) {
    if (!obs || !isCamera(*obs) || !std::isfinite(time)) return;
    auto& camera = cameras_[obs->sensorLabel];
    bool taken = false;
    if (afterGap && camera.gapFrames < options_.maxGapFramesPerCamera) {
        ++camera.gapFrames;
        if (camera.previous && !camera.previousTaken) {
            take(*camera.previous, camera.previousTime, "before a gap");
        }
        taken = take(*obs, time, "after a gap");
    }
    if (!taken && time >= camera.next) {
        char why[48];
        std::snprintf(why, sizeof why, "every %g s", options_.every);
        taken = take(*obs, time, why);
    }
    if (time >= camera.next) camera.next = std::floor(time / options_.every + 1) * options_.every;
    camera.previous = obs;
    camera.previousTime = time;
    camera.previousTaken = taken;
}

}  // namespace lodestone::inspect::report
