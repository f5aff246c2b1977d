#include <lodestone/datasets/MagneticRecordingImport.h>
#include <lodestone/io/RawlogPaths.h>
#include <lodestone/io/RawlogWriter.h>
#include <lodestone/io/TumTrajectory.h>
#include <lodestone/obs/CObservationMagnetometer.h>
#include <mrpt/obs/CObservationOdometry.h>

namespace lodestone::datasets {

MagneticImportResult writeMagneticRecording(const MagneticRecording& recording,
                                            const std::string& outRawlog,
                                            const OdometryDriftModel& model) {
    const auto odometry = synthesizeOdometry(recording, model);
    MagneticImportResult r;
    r.rawlog = outRawlog;
    r.groundTruth = io::rawlogStem(outRawlog) + ".gt.tum";
    io::RawlogWriter writer(
        outRawlog,
        io::RawlogWriter::Options{
            outRawlog.size() > 3 && outRawlog.substr(outRawlog.size() - 3) == ".gz" ? 6 : 0});
    io::TumTrajectoryWriter truth(r.groundTruth);
    std::size_t next = 0;  // next odometry sample
    for (std::size_t i = 0; i < recording.samples.size(); ++i) {
        const auto& s = recording.samples[i];
        const auto stamp = mrpt::Clock::fromDouble(s.t);
        if (next < odometry.size() && odometry[next].index == i) {
            mrpt::obs::CObservationOdometry odo;
            odo.sensorLabel = "ODOMETRY";
            odo.timestamp = stamp;
            odo.odometry = odometry[next].pose;
            writer.write(odo);
            ++next;
            ++r.odometrySamples;
        }
        obs::CObservationMagnetometer mag;
        mag.sensorLabel = "MAG";
        mag.timestamp = stamp;
        mag.field = s.field;
        mag.calibrated = recording.calibrated;
        writer.write(mag);
        ++r.magnetometerSamples;
        truth.write(s.t, mrpt::poses::CPose3D(s.x, s.y, 0, s.heading, 0, 0));
    }
    writer.close();
    truth.close();
    if (!recording.samples.empty()) {
        r.duration = recording.samples.back().t - recording.samples.front().t;
    }
    r.pathLength = recording.pathLength();
    return r;
}

}  // namespace lodestone::datasets
