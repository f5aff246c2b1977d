// The magnetometer-recording importers: CSV parsing errors, Aalto's heading from the direction
// of travel, Kok's levelling, the odometry drift model, and the rawlog they write. Real
// recordings are read in place from ../shared/data/magnetic (skipped when absent).
#include <gtest/gtest.h>
#include <lodestone/io/CsvTable.h>
#include <ImportApp.h>
#include <lodestone/datasets/MagneticRecordingImport.h>
#include <lodestone/io/RawlogSource.h>
#include <lodestone/io/TumTrajectory.h>
#include <lodestone/obs/CObservationMagnetometer.h>
#include <lodestone/obs/registerAllClasses.h>
#include <mrpt/obs/CObservationOdometry.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <sstream>

#include "TestPaths.h"

using namespace lodestone;
using namespace lodestone::io;
using namespace lodestone::datasets;
namespace fs = std::filesystem;

namespace {
const fs::path kMagnetic = test::sharedDataDir() / "magnetic";

void writeText(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

std::string errorOf(const std::function<void()>& f) {
    try {
        f();
    } catch (const std::exception& e) {
        return e.what();
    }
    return "";
}

// An Aalto-layout trial: the robot drives east 1 m, turns left on the spot, drives north 1 m;
// the world field is constant (20, 0, -40) uT.
void writeAaltoTrial(const fs::path& dir, int trial) {
    std::ofstream t(dir / (std::to_string(trial) + "-time.csv")),
        l(dir / (std::to_string(trial) + "-loc.csv")),
        m(dir / (std::to_string(trial) + "-mag.csv"));
    double time = 0;
    const auto put = [&](double x, double y) {
        t << time << "\n";
        l << x << "," << y << "\n";
        m << "20,0,-40\n";
        time += 0.02;
    };
    for (int i = 0; i <= 100; ++i) put(0.01 * i, 0);
    for (int i = 0; i < 20; ++i) put(1, 0);  // standing (turning)
    for (int i = 1; i <= 100; ++i) put(1, 0.01 * i);
}
}  // namespace

TEST(CsvTable, BadNumberAndMissingColumnNameFileAndLine) {
    test::TempDir dir;
    writeText(dir.file("a.csv"), "1,2,3\n4,x5,6\n");
    auto e = errorOf([&] { CsvTable::read(dir.file("a.csv")); });
    EXPECT_NE(e.find("a.csv: line 2"), std::string::npos) << e;
    EXPECT_NE(e.find("'x5'"), std::string::npos) << e;
    writeText(dir.file("b.csv"), "h1,h2,h3\n1,2,3\n\n4,5\n");
    e = errorOf([&] { CsvTable::read(dir.file("b.csv"), 3, 1); });
    EXPECT_NE(e.find("b.csv: line 4: expected 3 columns, found 2"), std::string::npos) << e;
    writeText(dir.file("c.csv"), "1,,3\n");
    e = errorOf([&] { CsvTable::read(dir.file("c.csv")); });
    EXPECT_NE(e.find("line 1: column 2"), std::string::npos) << e;
    e = errorOf([&] { CsvTable::read(dir.file("absent.csv")); });
    EXPECT_NE(e.find("absent.csv: cannot open"), std::string::npos) << e;
}

TEST(CsvTable, NanAndInfAreNumbersKeptForTheUserToJudge) {
    test::TempDir dir;
    writeText(dir.file("a.csv"), "1, nan ,inf\r\n-2.5e1,0,1\n");
    const auto t = CsvTable::read(dir.file("a.csv"));
    ASSERT_EQ(t.rows(), 2u);
    EXPECT_TRUE(std::isnan(t.at(0, 1)));
    EXPECT_TRUE(std::isinf(t.at(0, 2)));
    EXPECT_EQ(t.at(1, 0), -25.0);
    EXPECT_EQ(t.lineOf(1), 2u);
}

TEST(CsvTable, TextColumnsAreKeptAsWrittenTheRestStillNumbers) {
    test::TempDir dir;
    writeText(dir.file("a.csv"), "1,MagneticGpERD,3\n4,Orb,x\n");
    auto e = errorOf([&] { CsvTable::read(dir.file("a.csv"), 3, 0, {1}); });
    EXPECT_NE(e.find("a.csv: line 2: column 3"), std::string::npos) << e;
    writeText(dir.file("b.csv"), "1,MagneticGpERD,3\n4,Orb,6\n");
    const auto t = CsvTable::read(dir.file("b.csv"), 3, 0, {1});
    EXPECT_EQ(t.text(0, 1), "MagneticGpERD");
    EXPECT_EQ(t.text(1, 1), "Orb");
    EXPECT_TRUE(std::isnan(t.at(1, 1)));
    EXPECT_EQ(t.at(1, 2), 6.0);
    EXPECT_EQ(t.text(1, 2), "");  // a numeric column has no text
}

TEST(AaltoImport, HeadingFollowsTravelAndHoldsWhileStandingFieldTurnsIntoTheRobotFrame) {
    test::TempDir dir;
    writeAaltoTrial(dir.path(), 4);
    const auto rec = readAaltoTrial(dir.path().string(), 4);
    ASSERT_EQ(rec.samples.size(), 221u);
    EXPECT_NEAR(rec.pathLength(), 2.0, 1e-9);
    // Driving east: heading 0, the field as in the world.
    EXPECT_NEAR(rec.samples[50].heading, 0, 1e-9);
    EXPECT_NEAR(rec.samples[50].field.x, 20, 1e-9);
    EXPECT_NEAR(rec.samples[50].field.y, 0, 1e-9);
    // Standing: the heading held, not noise from a zero-length chord.
    EXPECT_NEAR(rec.samples[110].heading, rec.samples[100].heading, 1e-12);
    // Driving north: heading +90 deg, so the world's +x field is on the robot's right (-y).
    EXPECT_NEAR(rec.samples[200].heading, M_PI / 2, 1e-9);
    EXPECT_NEAR(rec.samples[200].field.x, 0, 1e-9);
    EXPECT_NEAR(rec.samples[200].field.y, -20, 1e-9);
    EXPECT_NEAR(rec.samples[200].field.z, -40, 1e-12);
}

TEST(AaltoImport, MismatchedFilesAreNamed) {
    test::TempDir dir;
    writeAaltoTrial(dir.path(), 2);
    writeText(dir.file("2-mag.csv"), "1,2,3\n");
    auto e = errorOf([&] { readAaltoTrial(dir.path().string(), 2); });
    EXPECT_NE(e.find("2-mag.csv: 1 rows, but"), std::string::npos) << e;
    e = errorOf([&] { readAaltoTrial(dir.path().string(), 7); });
    EXPECT_NE(e.find("7-time.csv: cannot open"), std::string::npos) << e;
    writeAaltoTrial(dir.path(), 3);
    writeText(dir.file("3-time.csv"), "0\n0.02\n0.01\n");
    e = errorOf([&] { readAaltoTrial(dir.path().string(), 3); });
    EXPECT_NE(e.find("3-time.csv: line 3: time does not increase"), std::string::npos) << e;
}

TEST(SyntheticOdometry, NoiseFreeModelReproducesTheReferenceAndASeedIsDeterministic) {
    test::TempDir dir;
    writeAaltoTrial(dir.path(), 1);
    const auto rec = readAaltoTrial(dir.path().string(), 1);
    OdometryDriftModel clean;
    clean.bias = clean.sp2 = clean.sh2 = 0;
    const auto odo = synthesizeOdometry(rec, clean);
    // 50 Hz recording, 10 Hz odometry.
    EXPECT_NEAR(static_cast<double>(odo.size()), rec.samples.back().t * 10 + 1, 1.0);
    const auto& start = rec.samples.front();
    for (const auto& o : odo) {
        const auto& s = rec.samples[o.index];
        // Reference = start pose (+) odometry.
        const auto p = mrpt::poses::CPose2D(start.x, start.y, start.heading) + o.pose;
        EXPECT_NEAR(p.x(), s.x, 1e-9);
        EXPECT_NEAR(p.y(), s.y, 1e-9);
        EXPECT_NEAR(std::remainder(p.phi() - s.heading, 2 * M_PI), 0, 1e-9);
    }
    OdometryDriftModel noisy;  // Kok & Solin's defaults
    const auto a = synthesizeOdometry(rec, noisy), b = synthesizeOdometry(rec, noisy);
    noisy.seed = 2;
    const auto c = synthesizeOdometry(rec, noisy);
    EXPECT_EQ(a.back().pose.x(), b.back().pose.x());
    EXPECT_NE(a.back().pose.x(), c.back().pose.x());
    // The bias turns the odometry: 0.005 rad/s over the run, plus noise of 0.01 rad per sample.
    const double turn = a.back().pose.phi() - (rec.samples.back().heading - start.heading);
    EXPECT_NEAR(turn, 0.005 * rec.samples.back().t, 4 * 0.01 * std::sqrt(double(a.size())));
    noisy.sp2 = -1;
    EXPECT_THROW(synthesizeOdometry(rec, noisy), std::invalid_argument);
}

TEST(MagneticImport, RawlogHoldsFieldAndOdometryAndTheGroundTruthSitsBeside) {
    lodestone::registerAllClasses();
    test::TempDir dir;
    writeAaltoTrial(dir.path(), 5);
    const auto r = writeMagneticRecording(readAaltoTrial(dir.path().string(), 5),
                                          dir.file("t5.rawlog"), OdometryDriftModel{});
    EXPECT_EQ(r.magnetometerSamples, 221u);
    EXPECT_EQ(r.groundTruth, dir.file("t5.gt.tum"));
    std::size_t mags = 0, odos = 0;
    io::RawlogSource source(r.rawlog);
    while (auto o = source.next()) {
        if (auto m = std::dynamic_pointer_cast<obs::CObservationMagnetometer>(o)) {
            ++mags;
            EXPECT_EQ(m->sensorLabel, "MAG");
            EXPECT_TRUE(m->calibrated);
            EXPECT_NEAR(m->field.z, -40, 1e-9);
        } else if (auto d = std::dynamic_pointer_cast<mrpt::obs::CObservationOdometry>(o)) {
            ++odos;
            EXPECT_FALSE(d->hasEncodersInfo);
        }
    }
    EXPECT_EQ(mags, 221u);
    EXPECT_EQ(odos, r.odometrySamples);
    const auto truth = readTumTrajectory(r.groundTruth);
    ASSERT_EQ(truth.size(), 221u);
    EXPECT_NEAR(truth.back().pose.y(), 1.0, 1e-9);
}

TEST(MagneticImport, RealKokWalksLevelToASteadyVerticalField) {
    for (const char* walk : {"eight.csv", "square.csv"}) {
        const fs::path csv = kMagnetic / "kok" / walk;
        if (!fs::exists(csv)) GTEST_SKIP() << "real data absent: " << csv;
        const auto rec = readKokWalk(csv.string());
        EXPECT_GT(rec.samples.size(), 400u);
        // Levelled right, the vertical component is the earth's (about -40..-50 uT here) plus
        // anomalies; levelled wrong it would swing with the device's tilt by tens of uT.
        double sum = 0, sq = 0;
        for (const auto& s : rec.samples) {
            sum += s.field.z;
            sq += s.field.z * s.field.z;
        }
        const double n = rec.samples.size(), mean = sum / n, sd = std::sqrt(sq / n - mean * mean);
        EXPECT_LT(mean, -35) << walk;
        EXPECT_LT(sd, 8) << walk;
    }
}

TEST(MagneticImport, RealAaltoTrialImportsThroughTheApp) {
    const fs::path dir = kMagnetic / "aalto" / "invensense";
    if (!fs::exists(dir / "1-time.csv")) GTEST_SKIP() << "real data absent: " << dir;
    lodestone::registerAllClasses();
    test::TempDir tmp;
    std::ostringstream out, err;
    const std::string outPath = tmp.file("a1.rawlog");
    const char* argv[] = {"lodestone-import", "aalto",  dir.c_str(), "1",
                          outPath.c_str(),    "--seed", "3"};
    ASSERT_EQ(datasets::runImportApp(7, argv, out, err), 0) << err.str();
    EXPECT_NE(out.str().find("8875 magnetometer"), std::string::npos) << out.str();
    EXPECT_EQ(readTumTrajectory(tmp.file("a1.gt.tum")).size(), 8875u);
}

TEST(MagneticImport, AppRefusesBadArgumentsAndNamesBadFiles) {
    test::TempDir tmp;
    std::ostringstream out, err;
    const std::string o = tmp.file("x.rawlog");
    const char* badTrial[] = {"lodestone-import", "aalto", "/nonexistent", "two", o.c_str()};
    EXPECT_EQ(datasets::runImportApp(5, badTrial, out, err), 2);
    EXPECT_NE(err.str().find("TRIAL 'two'"), std::string::npos) << err.str();
    const char* missing[] = {"lodestone-import", "kok", "/nonexistent/walk.csv", o.c_str()};
    EXPECT_EQ(datasets::runImportApp(4, missing, out, err), 1);
    EXPECT_NE(err.str().find("/nonexistent/walk.csv: cannot open"), std::string::npos) << err.str();
    writeText(tmp.file("walk.csv"), "t,tm,px,py,pz,q0,q1,q2,q3,mx,my,mz\n0,0,0,0,0,1,0,0,0,1,2\n");
    const std::string walk = tmp.file("walk.csv");
    const char* shortRow[] = {"lodestone-import", "kok", walk.c_str(), o.c_str()};
    EXPECT_EQ(datasets::runImportApp(4, shortRow, out, err), 1);
    EXPECT_NE(err.str().find("walk.csv: line 2: expected 12 columns, found 11"), std::string::npos)
        << err.str();
    const char* negative[] = {"lodestone-import", "kok", walk.c_str(), o.c_str(), "--sp2", "-1"};
    EXPECT_EQ(datasets::runImportApp(6, negative, out, err), 2);
    // Only a header, or an `inf` in a cell: named, and no rawlog of 0 samples / inf written.
    const char* run[] = {"lodestone-import", "kok", walk.c_str(), o.c_str()};
    writeText(walk, "t,tm,px,py,pz,q0,q1,q2,q3,mx,my,mz\n");
    EXPECT_EQ(datasets::runImportApp(4, run, out, err), 1);
    EXPECT_NE(err.str().find("walk.csv: 0 data rows"), std::string::npos) << err.str();
    writeText(walk, "t,tm,px,py,pz,q0,q1,q2,q3,mx,my,mz\n0,0,0,0,0,1,0,0,0,1,2,3\n"
                    "0.1,0,inf,0,0,1,0,0,0,1,2,3\n");
    EXPECT_EQ(datasets::runImportApp(4, run, out, err), 1);
    EXPECT_NE(err.str().find("walk.csv: line 3, column 3: not a finite number"), std::string::npos)
        << err.str();
    EXPECT_FALSE(fs::exists(o));
}

TEST(MagneticImport, AFieldInAnotherUnitIsRefusedNamingTheFileAndTheOptionAndReadRightWithIt) {
    test::TempDir tmp;
    // A walk east through a field of (20, 5, -40) uT written by writeKokWalk in each unit.
    MagneticRecording rec;
    for (int i = 0; i < 50; ++i)
        rec.samples.push_back({0.1 * i, 0.05 * i, 0, 0.01 * i, {20, 5.0 + 0.1 * i, -40}});
    const std::string uT = tmp.file("uT.csv"), gauss = tmp.file("gauss.csv"),
                      normalized = tmp.file("normalized.csv");
    writeKokWalk(rec, uT);
    writeKokWalk(rec, gauss, obs::MagneticUnit::gauss());
    writeKokWalk(rec, normalized, obs::MagneticUnit::normalized(45));
    const auto reference = readKokWalk(uT);
    for (const auto& [written, unit] :
         {std::pair{gauss, "gauss"}, std::pair{normalized, "normalized:45"}}) {
        const std::string file = written;  // (a structured binding is not captured before C++20)
        const auto e = errorOf([&] { readKokWalk(file); });
        EXPECT_NE(e.find(file + ": the field's median magnitude is"), std::string::npos) << e;
        EXPECT_NE(e.find("--unit gauss|uT|T|normalized:"), std::string::npos) << e;
        const auto read = readKokWalk(file, obs::MagneticUnit::parse(unit));
        ASSERT_EQ(read.samples.size(), reference.samples.size());
        for (std::size_t i = 0; i < read.samples.size(); ++i) {
            EXPECT_NEAR((read.samples[i].field - reference.samples[i].field).norm(), 0, 1e-9) << i;
            EXPECT_NEAR(read.samples[i].heading, reference.samples[i].heading, 1e-12) << i;
        }
        // The app: refused (exit 1, nothing written) without --unit, imported with it.
        std::ostringstream out, err;
        const std::string o = tmp.file("walk.rawlog");
        const char* without[] = {"lodestone-import", "kok", file.c_str(), o.c_str()};
        EXPECT_EQ(datasets::runImportApp(4, without, out, err), 1);
        EXPECT_NE(err.str().find("--unit"), std::string::npos) << err.str();
        EXPECT_FALSE(fs::exists(o));
        const char* with[] = {"lodestone-import", "kok", file.c_str(), o.c_str(), "--unit", unit};
        EXPECT_EQ(datasets::runImportApp(6, with, out, err), 0) << err.str();
        EXPECT_TRUE(fs::exists(o));
        fs::remove(o);
    }
    // An Aalto trial in gauss, the same.
    writeAaltoTrial(tmp.path(), 6);
    writeText(tmp.file("6-mag.csv"), [] {
        std::string m;
        for (int i = 0; i < 221; ++i) m += "0.2,0,-0.4\n";
        return m;
    }());
    const auto e = errorOf([&] { readAaltoTrial(tmp.path().string(), 6); });
    EXPECT_NE(e.find("6-mag.csv: the field's median magnitude is 0.4472 uT"), std::string::npos) << e;
    EXPECT_NEAR(readAaltoTrial(tmp.path().string(), 6, 0.05, obs::MagneticUnit::gauss())
                    .samples.front()
                    .field.norm(),
                std::sqrt(2000.0), 1e-9);
}
