#pragma once

#include <lodestone/view/SceneContent.h>

#include <mrpt/img/CImage.h>
#include <mrpt/opengl/COpenGLScene.h>

#include <string>

namespace lodestone::view {

/** Where the view looks from: orbiting `pointingAt` at `distance`, `azimuthDeg` around the
 * vertical from +x, `elevationDeg` above the floor (MRPT's CCamera). */
struct ViewCamera {
    double azimuthDeg{-60}, elevationDeg{50}, distance{10};
    double pointingAt[3]{0, 0, 0};
};

/** A camera that frames every node of `content` from the default direction. */
ViewCamera framing(const SceneContent& content);

/** Parses "AZ,EL" or "AZ,EL,DIST" or "AZ,EL,DIST,X,Y,Z" [deg, deg, m, m, m, m] over `base`;
 * throws std::invalid_argument naming the text when malformed. */
ViewCamera parseCamera(const std::string& text, const ViewCamera& base);

/** Renders `scene` off-screen (EGL: no display needed) at width x height. Throws
 * std::runtime_error when no OpenGL context can be made. */
mrpt::img::CImage renderScene(const mrpt::opengl::COpenGLScene& scene, const ViewCamera& camera,
                              unsigned width, unsigned height);

/** renderScene, written as a PNG; throws naming the file when it cannot be written. */
void writeScreenshot(const mrpt::opengl::COpenGLScene& scene, const ViewCamera& camera,
                     unsigned width, unsigned height, const std::string& pngPath);

}  // namespace lodestone::view
