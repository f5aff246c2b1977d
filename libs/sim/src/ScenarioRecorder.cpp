#include <lodestone/io/ImagesDirectory.h>
#include <lodestone/io/KidnapEvents.h>
#include <lodestone/io/RawlogPaths.h>
#include <lodestone/io/RawlogWriter.h>
#include <lodestone/io/TumTrajectory.h>
#include <lodestone/sim/ScenarioRecorder.h>
#include <mrpt/img/CImage.h>
#include <mrpt/obs/CObservation3DRangeScan.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <vector>

namespace lodestone::sim {

namespace {

// Moves a frame's colour image out of the observation into a PNG or JPEG file in `dir`. Depth
// stays in the rawlog, where gzip (OUT.rawlog.gz) packs it losslessly, better than MRPT's raw
// external depth files.
void externalize(mrpt::obs::CObservation3DRangeScan& scan, const CameraSpec& camera,
                 const std::string& dir, std::size_t k) {
    char name[64];
    std::snprintf(name, sizeof(name), "%s_%06zu", scan.sensorLabel.c_str(), k);
    const bool jpeg = camera.imageFormat == "jpg";
    const std::string rgbFile = std::string(name) + (jpeg ? ".jpg" : ".png");
    const cv::Mat bgr = scan.intensityImage.asCvMat<cv::Mat>(mrpt::img::SHALLOW_COPY);
    const std::vector<int> options =
        jpeg ? std::vector<int>{cv::IMWRITE_JPEG_QUALITY, camera.jpegQuality}
             : std::vector<int>{cv::IMWRITE_PNG_COMPRESSION, 1};
    if (!cv::imwrite(dir + "/" + rgbFile, bgr, options)) {
        throw std::runtime_error(dir + "/" + rgbFile + ": cannot write image");
    }
    scan.intensityImage.setExternalStorage(rgbFile);
}
}  // namespace

RecordingSummary recordScenario(SimulatorSource& source, const std::string& outRawlog,
                                const std::function<void(double)>& progress) {
    RecordingSummary r;
    const std::string stem = io::rawlogStem(outRawlog);
    r.rawlog = outRawlog;
    r.groundTruth = stem + ".gt.tum";
    r.events = stem + ".events.txt";
    io::prepareOutputFile(outRawlog);
    const bool external = source.scenario().camera.externalImages;
    if (external) {
        r.imagesDir = io::findImagesDirectory(outRawlog);
        std::filesystem::create_directories(r.imagesDir);
        mrpt::img::CImage::setImagesPathBase(r.imagesDir);
    }

    // The events file first: it is known before the run.
    io::writeKidnapEvents(r.events, source.scenario().name, kidnapRecords(source));

    io::RawlogWriter writer(outRawlog, {io::isGzipPath(outRawlog) ? 1 : 0});
    io::TumTrajectoryWriter gt(r.groundTruth);
    double lastReported = -1;
    while (auto obs = source.next()) {
        const double t = source.lastTime();
        if (auto scan = std::dynamic_pointer_cast<mrpt::obs::CObservation3DRangeScan>(obs)) {
            if (external) externalize(*scan, source.scenario().camera, r.imagesDir, r.frames);
            ++r.frames;
        }
        writer.write(*obs);
        gt.write(source.startTime() + t, source.truePose3D(t));
        ++r.observations;
        r.duration = t;
        if (progress && t - lastReported >= 5.0) {
            progress(t / std::max(1e-9, source.duration()));
            lastReported = t;
        }
    }
    writer.close();
    gt.close();
    return r;
}

}  // namespace lodestone::sim
