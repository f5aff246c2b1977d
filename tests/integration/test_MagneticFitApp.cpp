// lodestone-magfit on recordings made here: a field along the path drawn from a GP with a
// known length scale (random Fourier features of the squared-exponential kernel) is fitted
// back; bad inputs are clear errors with exit code 1 or 2.
#include <gtest/gtest.h>
#include <lodestone/datasets/MagneticRecordingImport.h>
#include <MagneticFitApp.h>
#include <lodestone/io/RawlogSource.h>
#include <lodestone/io/RawlogWriter.h>
#include <lodestone/obs/CObservationMagnetometer.h>
#include <lodestone/obs/registerAllClasses.h>

#include <cmath>
#include <fstream>
#include <random>
#include <regex>
#include <sstream>

#include "TestPaths.h"

namespace {

struct AppResult {
    int code;
    std::string out, err;
};

AppResult runFit(std::vector<std::string> args) {
    args.insert(args.begin(), "lodestone-magfit");
    std::vector<const char*> argv;
    for (const auto& a : args) argv.push_back(a.c_str());
    std::ostringstream out, err;
    const int code = lodestone::slamapp::runMagneticFitApp(static_cast<int>(argv.size()),
                                                           argv.data(), out, err);
    return {code, out.str(), err.str()};
}

double valueOf(const std::string& text, const std::string& key) {
    std::smatch m;
    return std::regex_search(text, m, std::regex(key + R"(\s*=\s*([0-9.eE+-]+))")) ? std::stod(m[1])
                                                                                : -1;
}

// 60 m round a 4 m-radius circle at 1 m/s, 50 Hz; the vertical field is the earth's plus a GP
// draw of the given length scale and amplitude along the path plus reading noise of 0.2 uT;
// odometry without noise.
std::string writeGpRecording(const std::string& path, double lengthScale, double sigmaF) {
    std::mt19937 rng(5);
    std::normal_distribution<double> n(0, 1);
    std::uniform_real_distribution<double> phase(0, 2 * M_PI);
    const int features = 400;
    std::vector<double> omega, offset;
    for (int k = 0; k < features; ++k) {
        omega.push_back(n(rng) / lengthScale);
        offset.push_back(phase(rng));
    }
    lodestone::datasets::MagneticRecording rec;
    rec.name = "gp draw";
    for (int i = 0; i <= 3000; ++i) {
        const double s = 0.02 * i, a = s / 4.0;
        double g = 0;
        for (int k = 0; k < features; ++k) g += std::cos(omega[k] * s + offset[k]);
        g *= sigmaF * std::sqrt(2.0 / features);
        lodestone::datasets::MagneticRecordingSample x;
        x.t = 0.02 * i;
        x.x = 4 * std::sin(a);
        x.y = 4 * (1 - std::cos(a));
        x.heading = a;
        x.field = {0, 0, -40 + g + 0.2 * n(rng)};
        rec.samples.push_back(x);
    }
    lodestone::datasets::OdometryDriftModel exact;
    exact.bias = exact.sp2 = exact.sh2 = 0;
    return lodestone::datasets::writeMagneticRecording(rec, path, exact).rawlog;
}

}  // namespace

TEST(MagneticFitApp, RecoversTheLengthScaleOfAGpDrawnField) {
    lodestone::test::TempDir dir;
    const auto rawlog = writeGpRecording(dir.file("gp.rawlog"), 0.4, 3.0);
    const auto r = runFit({rawlog, "--stretch", "10"});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("[MagneticGpERD]"), std::string::npos) << r.out;
    EXPECT_NEAR(valueOf(r.out, "gp_length_scale"), 0.4, 0.1) << r.out;
    EXPECT_NEAR(valueOf(r.out, "gp_sigma_f"), 3.0, 1.2) << r.out;
    // The noise of what the GP sees: 0.05 m bins of readings 0.02 m apart average 2.5 of them.
    EXPECT_NEAR(valueOf(r.out, "gp_sigma_n"), 0.2 / std::sqrt(2.5), 0.03) << r.out;
}

TEST(MagneticFitApp, BadInputsAreNamedErrors) {
    lodestone::test::TempDir dir;
    const auto rawlog = writeGpRecording(dir.file("gp.rawlog"), 0.4, 3.0);
    auto r = runFit({dir.file("absent.rawlog")});
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find("absent.rawlog"), std::string::npos) << r.err;
    r = runFit({rawlog, "--sensor", "NOPE"});
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find("NOPE"), std::string::npos) << r.err;
    r = runFit({rawlog, "--mode", "sideways"});
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find("sideways"), std::string::npos) << r.err;
    r = runFit({rawlog, "--stretch", "200"});  // over twice the 60 m path
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find("one stretch"), std::string::npos) << r.err;
    r = runFit({rawlog, "--stretch", "-1"});
    EXPECT_EQ(r.code, 2);
    std::ofstream(dir.file("typo.ini")) << "[MagneticGpERD]\ngp_lenght_scale = 0.3\n";
    r = runFit({rawlog, "--config", dir.file("typo.ini")});
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find("gp_lenght_scale"), std::string::npos) << r.err;
    r = runFit({dir.path().string()});  // a directory, not a rawlog
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find("a directory"), std::string::npos) << r.err;
    r = runFit({rawlog, "--step", "1e-9"});  // 10^10 points a stretch: refused, not attempted
    EXPECT_EQ(r.code, 2);
    EXPECT_NE(r.err.find("--step"), std::string::npos) << r.err;
}

TEST(MagneticFitApp, AMagnetometerInAnotherUnitIsRefusedOrReadInIt) {
    // The GP draw's readings (|B| about 40 uT) written in gauss: read as microtesla they are
    // refused naming the rawlog and the option; with it, the same fit as in microtesla.
    lodestone::test::TempDir dir;
    const auto uT = writeGpRecording(dir.file("gp.rawlog"), 0.4, 3.0);
    lodestone::registerAllClasses();
    {
        lodestone::io::RawlogSource in(uT);
        lodestone::io::RawlogWriter outGauss(dir.file("gauss.rawlog"), {});
        while (auto obs = in.next()) {
            if (auto m = std::dynamic_pointer_cast<lodestone::obs::CObservationMagnetometer>(obs))
                m->field *= 0.01;
            outGauss.write(*obs);
        }
        outGauss.close();
    }
    auto r = runFit({dir.file("gauss.rawlog")});
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find("gauss.rawlog: its magnetometer, read as uT"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("--magnetic-unit"), std::string::npos) << r.err;
    const auto asGauss = runFit({dir.file("gauss.rawlog"), "--magnetic-unit", "gauss"});
    const auto asUT = runFit({uT});
    ASSERT_EQ(asGauss.code, 0) << asGauss.err;
    EXPECT_NEAR(valueOf(asGauss.out, "gp_length_scale"), valueOf(asUT.out, "gp_length_scale"), 1e-3);
    EXPECT_EQ(runFit({uT, "--magnetic-unit", "furlongs"}).code, 2);
}
