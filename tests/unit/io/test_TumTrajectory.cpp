// A TUM trajectory file read strictly: every line that cannot be a pose is named by its line
// number, instead of an MRPT call-stack dump (zero quaternion), an "ATE inf" (1e308) or poses
// dropped without a word (timestamps out of order).
#include <gtest/gtest.h>
#include <lodestone/io/TumTrajectory.h>

#include <fstream>

#include "TestPaths.h"

using lodestone::io::readTumTrajectory;

namespace {
std::string errorReading(const std::string& path, const std::string& text) {
    std::ofstream(path) << text;
    try {
        readTumTrajectory(path);
    } catch (const std::exception& e) {
        return e.what();
    }
    return "";
}
}  // namespace

TEST(TumTrajectory, EveryBadLineIsNamed) {
    lodestone::test::TempDir dir;
    const std::string good = "# timestamp tx ty tz qx qy qz qw\n1.0 0 0 0 0 0 0 1\n";
    const struct {
        const char* line;
        const char* says;
    } cases[] = {{"2.0 0 0 0 0 0 0 0\n", "quaternion is zero"},
                 {"2.0 1e308 0 0 0 0 0 1\n", "beyond 1e6 m"},
                 {"0.5 0 0 0 0 0 0 1\n", "before the previous"},
                 {"2.0 nan 0 0 0 0 0 1\n", "not a finite number"},
                 {"2.0 0 0 inf 0 0 0 1\n", "not a finite number"},
                 {"2.0 0 0 0 0 0 1\n", "expected 'timestamp"},
                 {"two 0 0 0 0 0 0 1\n", "expected 'timestamp"}};
    for (const auto& c : cases) {
        const auto path = dir.file("t.tum");
        const std::string e = errorReading(path, good + c.line);
        EXPECT_NE(e.find(path + ": line 3"), std::string::npos) << c.line << " -> " << e;
        EXPECT_NE(e.find(c.says), std::string::npos) << c.line << " -> " << e;
    }
}

TEST(TumTrajectory, AQuaternionNotOfUnitLengthIsNormalizedAndEqualTimesPass) {
    lodestone::test::TempDir dir;
    std::ofstream(dir.file("t.tum")) << "1.0 1 2 3 0 0 0 2\n2.0 1 2 3 0 0 2 2\n2.0 1 2 3 0 0 2 2\n";
    const auto t = readTumTrajectory(dir.file("t.tum"));
    ASSERT_EQ(t.size(), 3u);
    EXPECT_NEAR(t[0].pose.yaw(), 0.0, 1e-12);
    EXPECT_NEAR(t[1].pose.yaw(), M_PI / 2, 1e-12);
    EXPECT_NEAR(t[1].pose.x(), 1.0, 1e-12);
}
