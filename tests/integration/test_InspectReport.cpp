// `lodestone-inspect report` as a user runs it: the page of the bundled sample (with a SLAM run
// on it) in headless Chromium, gaps and backwards timestamps in its table, a damaged rawlog.
#include <gtest/gtest.h>
#include <lodestone/io/RawlogWriter.h>
#include <lodestone/obs/CObservationMagnetometer.h>
#include <lodestone/obs/registerAllClasses.h>

#include <filesystem>
#include <fstream>
#include <regex>

#include "StockTools.h"
#include "TestPaths.h"

namespace fs = std::filesystem;
using lodestone::test::runCommand;

namespace {
const std::string kInspect = LODESTONE_INSPECT_BINARY;
const std::string kSlam = LODESTONE_SLAM_BINARY;
const std::string kOffice = LODESTONE_OFFICE_RAWLOG;

bool haveChromium() { return runCommand("command -v chromium").exitCode == 0; }

// Checks run inside the page: every image decoded, no error event, no console.error. Written
// into a copy of the page (the report itself carries no script) and read back from the DOM
// Chromium dumps after the load event.
const char* kPageCheck = R"(<script>
window.__errors = [];
window.addEventListener('error', function (e) {
  __errors.push(e.target && e.target.src ? 'not loaded: ' + e.target.src : 'error: ' + e.message);
}, true);
var originalError = console.error;
console.error = function () {
  __errors.push('console.error: ' + Array.prototype.join.call(arguments, ' '));
  originalError.apply(console, arguments);
};
window.addEventListener('load', function () {
  var images = Array.prototype.slice.call(document.images);
  var broken = images.filter(function (i) { return !(i.complete && i.naturalWidth > 0); })
                     .map(function (i) { return i.src; });
  document.body.setAttribute('data-check', 'images=' + images.length + ';broken=' +
      broken.length + ';errors=' + __errors.length + ';' + broken.concat(__errors).join('|'));
});
</script>
)";

struct PageCheck {
    int images{-1}, broken{-1}, errors{-1};
    std::string detail, output;
};

PageCheck checkInChromium(const fs::path& reportDir) {
    std::string html = lodestone::test::readTextFile((reportDir / "index.html").string());
    html.insert(html.find("<head>") + 6, std::string("\n") + kPageCheck);
    const fs::path check = reportDir / "page_check.html";
    std::ofstream(check) << html;
    PageCheck c;
    const auto r = runCommand("timeout 120 chromium --headless --no-sandbox --disable-gpu "
                              "--virtual-time-budget=5000 --dump-dom 'file://" +
                              check.string() + "' 2>/dev/null");
    c.output = r.output;
    std::smatch m;
    if (std::regex_search(r.output, m,
                          std::regex("data-check=\"images=([0-9]+);broken=([0-9]+);errors=([0-9]+);([^\"]*)\""))) {
        c.images = std::stoi(m[1]);
        c.broken = std::stoi(m[2]);
        c.errors = std::stoi(m[3]);
        c.detail = m[4];
    }
    fs::remove(check);
    return c;
}

// A magnetometer at 100 Hz for 10 s, the second from 4 s to 5 s missing, and one reading at
// 7 s stamped 6.7 s (0.29 s older than the one before it).
void writeGapAndBackwardsRawlog(const std::string& path) {
    lodestone::registerAllClasses();
    lodestone::io::RawlogWriter w(path);
    lodestone::obs::CObservationMagnetometer m;
    m.sensorLabel = "MAG";
    m.field = {20, 5, -40};
    for (int i = 0; i < 1000; ++i) {
        const double t = 0.01 * i;
        if (t >= 4.0 && t < 5.0) continue;
        m.timestamp = mrpt::Clock::fromDouble(1700000000.0 + (i == 700 ? t - 0.3 : t));
        w.write(m);
    }
    w.close();
}
}  // namespace

TEST(InspectReport, TheBundledSampleWithItsSlamRunOpensInChromium) {
    lodestone::test::TempDir dir;
    const std::string gt = std::regex_replace(kOffice, std::regex("rawlog.gz$"), "gt.tum");
    auto r = runCommand(kSlam + " --rawlog " + kOffice + " --config " + LODESTONE_CONFIG_INI_DIR +
                        "/slam/slam.ini --quiet --mesh --out " + dir.file("slam"));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    r = runCommand(kInspect + " report " + kOffice + " --out " + dir.file("report") + " --slam " +
                   dir.file("slam") + " --ground-truth " + gt + " -q");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const fs::path report = dir.path() / "report";
    const std::string html = lodestone::test::readTextFile((report / "index.html").string());
    // Self-contained: nothing fetched from elsewhere, every picture a file in the folder.
    EXPECT_EQ(html.find("http://"), std::string::npos);
    EXPECT_EQ(html.find("https://"), std::string::npos);
    std::size_t images = 0;
    const std::regex srcAttribute("src=\"([^\"]+)\"");
    for (std::sregex_iterator it(html.begin(), html.end(), srcAttribute), end;
         it != end; ++it) {
        ++images;
        const std::string src = (*it)[1];
        EXPECT_EQ(src.find(':'), std::string::npos) << src;
        EXPECT_TRUE(fs::exists(report / src)) << src;
    }
    // The rawlog's charts (timeline, two magnetometers, odometry), three thumbnails of two
    // images each, and the SLAM section's five (trajectory, graph, the 3D view, field map, node
    // time) - four where this machine cannot render off-screen, which the page then says.
    const bool view3d = fs::exists(report / "slam_view3d.png");
    if (!view3d) {
        EXPECT_NE(html.find("not shown: the 3D view"), std::string::npos);
    }
    EXPECT_EQ(images, 4u + 6u + (view3d ? 5u : 4u));
    // The run has a dense model: the 3D picture is of it.
    if (view3d) {
        EXPECT_NE(html.find("the dense model (mesh.ply"), std::string::npos);
    }
    for (const char* section : {"Summary", "Sensors", "Camera frames", "SLAM run"}) {
        EXPECT_NE(html.find(std::string("<h2>") + section + "</h2>"), std::string::npos) << section;
    }
    EXPECT_NE(html.find("ATE RMSE against"), std::string::npos);

    if (!haveChromium()) {
        GTEST_SKIP() << "chromium not installed (scripts/install-deps.sh installs it): the page "
                        "was checked as text only";
    }
    const auto c = checkInChromium(report);
    ASSERT_GE(c.images, 0) << "no check result in Chromium's DOM dump:\n" << c.output.substr(0, 2000);
    EXPECT_EQ(c.images, static_cast<int>(images));
    EXPECT_EQ(c.broken, 0) << c.detail;
    EXPECT_EQ(c.errors, 0) << c.detail;
    // The README's picture of a report page.
    const fs::path shots = LODESTONE_SCREENSHOT_DIR;
    fs::create_directories(shots);
    r = runCommand("timeout 120 chromium --headless --no-sandbox --disable-gpu --hide-scrollbars "
                   "--window-size=1280,2400 --screenshot='" + (shots / "report.png").string() +
                   "' 'file://" + (report / "index.html").string() + "' 2>&1");
    EXPECT_TRUE(fs::exists(shots / "report.png")) << r.output;
}

TEST(InspectReport, AGapAndABackwardsTimestampShowInTheTable) {
    lodestone::test::TempDir dir;
    const std::string rawlog = dir.file("gap.rawlog");
    writeGapAndBackwardsRawlog(rawlog);
    const auto r = runCommand(kInspect + " report " + rawlog + " --out " + dir.file("report") + " -q");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const std::string html = lodestone::test::readTextFile(dir.file("report/index.html"));
    // The sensor's row: ... gaps 1, largest gap ~1.0 s, backwards 1, largest backwards 0.3 s,
    // the nonzero cells marked.
    std::smatch m;
    ASSERT_TRUE(std::regex_search(
        html, m,
        std::regex("<td class=\"l\">MAG</td>.*?<td class=\"bad\">([0-9]+)</td><td "
                   "class=\"bad\">([0-9.]+)</td><td class=\"bad\">([0-9]+)</td><td "
                   "class=\"bad\">([0-9.]+)</td>")))
        << html.substr(html.find("<h2>Sensors"), 3000);
    EXPECT_EQ(m[1], "1");
    EXPECT_NEAR(std::stod(m[2]), 1.01, 0.005);
    EXPECT_EQ(m[3], "1");
    EXPECT_NEAR(std::stod(m[4]), 0.29, 0.005);  // 6.70 against the 6.99 before it
    // And each is listed with when it happened.
    EXPECT_NE(html.find("<td class=\"l\">MAG</td><td>gap</td><td>3.990</td>"), std::string::npos);
    EXPECT_NE(html.find("<td class=\"l\">MAG</td><td>backwards</td><td>6.700</td>"), std::string::npos);
}

TEST(InspectReport, ADamagedRawlogGetsThePageOfWhatWasReadAndExitsOne) {
    lodestone::test::TempDir dir;
    const std::string rawlog = dir.file("gap.rawlog");
    writeGapAndBackwardsRawlog(rawlog);
    fs::resize_file(rawlog, fs::file_size(rawlog) / 2 + 7);  // cut inside an entry
    const auto r = runCommand(kInspect + " report " + rawlog + " --out " + dir.file("report") + " -q");
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_NE(r.output.find(rawlog), std::string::npos) << r.output;
    const std::string html = lodestone::test::readTextFile(dir.file("report/index.html"));
    EXPECT_NE(html.find("class=\"error\""), std::string::npos);
    EXPECT_NE(html.find("<h2>Sensors</h2>"), std::string::npos);
}

TEST(InspectReport, BadArgumentsAreRefusedBeforeAnyWork) {
    lodestone::test::TempDir dir;
    auto r = runCommand(kInspect + " report " + kOffice + " --out " + dir.file("r") + " --slam " +
                        dir.file("no_such_run"));
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_NE(r.output.find("no_such_run"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir.file("r/index.html")));
    r = runCommand(kInspect + " report " + kOffice + " --out " + dir.file("r") + " --thumbnail-every 0");
    EXPECT_EQ(r.exitCode, 2) << r.output;
    r = runCommand(kInspect + " report /nonexistent.rawlog --out " + dir.file("r"));
    EXPECT_EQ(r.exitCode, 1) << r.output;
}

TEST(InspectReport, ASecondReportInTheSameFolderLeavesNothingStaleAndNothingElseRemoved) {
    lodestone::test::TempDir dir;
    const std::string out = dir.file("report");
    auto r = runCommand(kInspect + " report " + kOffice + " --out " + out + " --thumbnail-every 2 -q");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const auto count = [&](const fs::path& folder) {
        std::size_t n = 0;
        for (const auto& e : fs::directory_iterator(folder)) n += e.is_regular_file();
        return n;
    };
    const std::size_t many = count(fs::path(out) / "thumbs");
    std::ofstream(out + "/notes.txt") << "the user's own file\n";
    r = runCommand(kInspect + " report " + kOffice + " --out " + out + " --thumbnail-every 10 -q");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_LT(count(fs::path(out) / "thumbs"), many);
    EXPECT_EQ(count(fs::path(out) / "thumbs"), 6u);  // 3 frames x (colour, depth)
    EXPECT_TRUE(fs::exists(out + "/notes.txt"));
}

// A saved map on the page: its summary and its picture, beside the rawlog's sections; a damaged
// map is refused before any page is written.
TEST(InspectReport, ASavedMapGetsItsSection) {
    lodestone::test::TempDir dir;
    const std::string map = std::string(LODESTONE_TEST_DATA_DIR) + "/map_v1";
    auto r = runCommand(kInspect + " report " + kOffice + " --out " + dir.file("report") +
                        " --map " + map + " -q");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const std::string html = lodestone::test::readTextFile(dir.file("report/index.html"));
    EXPECT_NE(html.find("<h2>Saved map</h2>"), std::string::npos);
    EXPECT_NE(html.find("saved_map.png"), std::string::npos);
    EXPECT_TRUE(fs::exists(dir.path() / "report" / "saved_map.png"));
    const auto section = html.find("<h2>Saved map</h2>");
    ASSERT_NE(section, std::string::npos);
    EXPECT_NE(html.find("nodes", section), std::string::npos) << "the summary's text";
    EXPECT_LT(html.find("<h2>Summary</h2>"), html.find("<h2>Saved map</h2>"));

    fs::copy(map, dir.path() / "broken_map", fs::copy_options::recursive);
    fs::permissions(dir.path() / "broken_map", fs::perms::owner_all, fs::perm_options::add);
    for (const auto& f : fs::directory_iterator(dir.path() / "broken_map")) {
        fs::permissions(f.path(), fs::perms::owner_write, fs::perm_options::add);
    }
    std::ofstream(dir.file("broken_map/nodes.bin"), std::ios::trunc) << "not a map";
    r = runCommand(kInspect + " report " + kOffice + " --out " + dir.file("report2") + " --map " +
                   dir.file("broken_map") + " -q");
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_NE(r.output.find("nodes.bin"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir.path() / "report2" / "index.html"));
}
