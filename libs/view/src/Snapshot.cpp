#include <lodestone/view/Snapshot.h>

#include <mrpt/opengl/CFBORender.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <mutex>
#include <sstream>
#include <thread>
#include <stdexcept>
#include <vector>

namespace lodestone::view {

namespace {
constexpr double kFieldOfViewDeg = 30;  // CCamera's default vertical field of view
}

ViewCamera framing(const SceneContent& content) {
    ViewCamera camera;
    if (content.nodes.empty()) return camera;
    double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
    for (const auto& n : content.nodes) {
        const double p[3] = {n.pose.x(), n.pose.y(), n.pose.z()};
        for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], p[k]), hi[k] = std::max(hi[k], p[k]);
    }
    double radius = 0;
    for (int k = 0; k < 3; ++k) {
        camera.pointingAt[k] = 0.5 * (lo[k] + hi[k]);
        radius = std::max(radius, 0.5 * (hi[k] - lo[k]));
    }
    // The box's longest half-side in view with a margin (at least a metre across).
    camera.distance = std::max(1.0, 1.2 * radius) /
                      std::tan(0.5 * kFieldOfViewDeg * M_PI / 180);
    return camera;
}

ViewCamera parseCamera(const std::string& text, const ViewCamera& base) {
    std::vector<double> values;
    std::stringstream in(text);
    std::string item;
    while (std::getline(in, item, ',')) {
        std::size_t used = 0;
        double v = 0;
        try {
            v = std::stod(item, &used);
        } catch (const std::exception&) {
            used = 0;
        }
        if (used == 0 || used != item.size() || !std::isfinite(v))
            throw std::invalid_argument("camera '" + text + "': '" + item + "' is not a number");
        values.push_back(v);
    }
    if (values.size() != 2 && values.size() != 3 && values.size() != 6)
        throw std::invalid_argument("camera '" + text +
                                    "': expected AZ,EL or AZ,EL,DIST or AZ,EL,DIST,X,Y,Z");
    ViewCamera c = base;
    c.azimuthDeg = values[0];
    c.elevationDeg = values[1];
    if (values.size() >= 3) {
        if (!(values[2] > 0)) throw std::invalid_argument("camera '" + text + "': the distance must be > 0");
        c.distance = values[2];
    }
    if (values.size() == 6)
        for (int k = 0; k < 3; ++k) c.pointingAt[k] = values[3 + k];
    return c;
}

namespace {

/** MRPT keeps each object's GPU buffers in the object, for the context that drew it first: a
 * scene drawn by a second context fails. So the process has one EGL context (the first
 * renderer's, kept), and renderers of other sizes draw in it; all on the thread that made it. */
mrpt::opengl::CFBORender& rendererFor(unsigned width, unsigned height,
                                      std::unique_ptr<mrpt::opengl::CFBORender>& local) {
    static std::unique_ptr<mrpt::opengl::CFBORender> first;
    static unsigned firstWidth = 0, firstHeight = 0;
    static std::thread::id owner;
    if (!first) {
        first = std::make_unique<mrpt::opengl::CFBORender>(width, height);
        firstWidth = width;
        firstHeight = height;
        owner = std::this_thread::get_id();
    }
    if (std::this_thread::get_id() != owner)
        throw std::runtime_error("off-screen rendering from a second thread (one context per process)");
    if (width == firstWidth && height == firstHeight) return *first;
    mrpt::opengl::CFBORender::Parameters p(width, height);
    p.create_EGL_context = false;
    local = std::make_unique<mrpt::opengl::CFBORender>(p);
    return *local;
}

}  // namespace

mrpt::img::CImage renderScene(const mrpt::opengl::COpenGLScene& scene, const ViewCamera& camera,
                              unsigned width, unsigned height) {
    static std::mutex one;
    std::lock_guard<std::mutex> lock(one);
    mrpt::img::CImage image;
    try {
        std::unique_ptr<mrpt::opengl::CFBORender> local;
        auto& render = rendererFor(width, height, local);
        auto& c = render.getCamera(scene);
        c.setPointingAt(static_cast<float>(camera.pointingAt[0]), static_cast<float>(camera.pointingAt[1]),
                        static_cast<float>(camera.pointingAt[2]));
        c.setZoomDistance(static_cast<float>(camera.distance));
        c.setAzimuthDegrees(static_cast<float>(camera.azimuthDeg));
        c.setElevationDegrees(static_cast<float>(camera.elevationDeg));
        c.setProjectiveFOVdeg(static_cast<float>(kFieldOfViewDeg));
        render.render_RGB(scene, image);
    } catch (const std::exception& e) {
        throw std::runtime_error(std::string("off-screen rendering failed (no EGL / OpenGL context?): ") + e.what());
    }
    return image;
}

void writeScreenshot(const mrpt::opengl::COpenGLScene& scene, const ViewCamera& camera,
                     unsigned width, unsigned height, const std::string& pngPath) {
    const mrpt::img::CImage image = renderScene(scene, camera, width, height);
    if (!image.saveToFile(pngPath)) throw std::runtime_error(pngPath + ": cannot be written");
}

}  // namespace lodestone::view
