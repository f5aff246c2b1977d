#include <lodestone/datasets/RgbdFrameImport.h>
#include <mrpt/obs/CObservation3DRangeScan.h>

#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <stdexcept>

namespace lodestone::datasets {

void writeRgbdFrame(io::RawlogWriter& writer, double timestamp, const std::string& colourPath,
                    const std::string& depthPath, const RgbdFrameOptions& o) {
    if (!std::filesystem::exists(colourPath))
        throw std::runtime_error(colourPath + ": missing colour image");
    cv::Mat d = cv::imread(depthPath, cv::IMREAD_UNCHANGED);
    if (d.empty() || d.type() != CV_16UC1)
        throw std::runtime_error(depthPath + ": missing or not a 16-bit depth image");
    if (o.registration) {
        // (the colour image is read for its size only: its pixels are referenced, not copied)
        const cv::Mat colour = cv::imread(colourPath, cv::IMREAD_UNCHANGED);
        if (colour.empty()) throw std::runtime_error(colourPath + ": not an image OpenCV reads");
        d = registerDepthToColour(d, *o.registration, o.intrinsics, colour.size(), o.depthScale,
                                  o.invalidDepthFrom);
    }
    auto obs = mrpt::obs::CObservation3DRangeScan::Create();
    obs->timestamp = mrpt::Clock::fromDouble(timestamp);
    obs->sensorLabel = o.sensorLabel;
    obs->sensorPose = mrpt::poses::CPose3D();  // the camera is the robot: a handheld sequence
    auto& cam = obs->cameraParams;
    cam.ncols = static_cast<uint32_t>(d.cols);
    cam.nrows = static_cast<uint32_t>(d.rows);
    cam.fx(o.intrinsics.fx);
    cam.fy(o.intrinsics.fy);
    cam.cx(o.intrinsics.cx);
    cam.cy(o.intrinsics.cy);
    obs->cameraParamsIntensity = cam;
    obs->range_is_depth = true;
    obs->rangeUnits = static_cast<float>(1.0 / o.depthScale);
    obs->hasRangeImage = true;
    obs->rangeImage_setSize(d.rows, d.cols);
    for (int y = 0; y < d.rows; ++y) {
        for (int x = 0; x < d.cols; ++x) {
            const uint16_t v = d.at<uint16_t>(y, x);
            obs->rangeImage(y, x) = v >= o.invalidDepthFrom ? 0 : v;
        }
    }
    obs->hasIntensityImage = true;
    obs->intensityImage.setExternalStorage(std::filesystem::absolute(colourPath).string());
    writer.write(*obs);
}

}  // namespace lodestone::datasets
