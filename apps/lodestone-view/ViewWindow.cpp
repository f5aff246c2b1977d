#include <ViewWindow.h>

#include <mrpt/gui/CDisplayWindow3D.h>

#include <chrono>
#include <map>
#include <thread>

namespace lodestone::view {

namespace {

/** Flips the visibility of every layer whose name starts with `prefix`. */
void toggle(mrpt::opengl::COpenGLScene& scene, const std::string& prefix, std::ostream& out) {
    for (auto& object : *scene.getViewport()) {
        if (object->getName().rfind(prefix, 0) != 0) continue;
        object->setVisibility(!object->isVisible());
        out << object->getName() << (object->isVisible() ? " shown\n" : " hidden\n");
    }
}

}  // namespace

void showWindow(const mrpt::opengl::COpenGLScene::Ptr& scene, const ViewCamera& camera,
                const std::string& title, std::ostream& out) {
    mrpt::gui::CDisplayWindow3D window("lodestone-view " + title, 1280, 960);
    {
        auto& shown = window.get3DSceneAndLock();
        shown = scene;
        window.unlockAccess3DScene();
    }
    window.setCameraPointingToPoint(static_cast<float>(camera.pointingAt[0]),
                                    static_cast<float>(camera.pointingAt[1]),
                                    static_cast<float>(camera.pointingAt[2]));
    window.setCameraZoom(static_cast<float>(camera.distance));
    window.setCameraAzimuthDeg(static_cast<float>(camera.azimuthDeg));
    window.setCameraElevationDeg(static_cast<float>(camera.elevationDeg));
    window.repaint();
    out << "keys: n nodes, o odometry, l closures, r refused, c cloud, m mesh, t truth, f floor; q quits\n";
    static const std::map<int, std::string> layers{{'n', "nodes"},   {'o', "odometry"}, {'l', "closures"}, {'m', "mesh"},
                                                   {'r', "refused"}, {'c', "cloud"},    {'t', "truth"},
                                                   {'f', "floor"}};
    while (window.isOpen()) {
        if (window.keyHit()) {
            const int key = window.getPushedKey();
            if (key == 'q' || key == 'Q' || key == 27) break;
            const auto it = layers.find(key >= 'A' && key <= 'Z' ? key - 'A' + 'a' : key);
            if (it != layers.end()) {
                window.get3DSceneAndLock();
                toggle(*scene, it->second, out);
                window.unlockAccess3DScene();
                window.repaint();
            }
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
}

}  // namespace lodestone::view
