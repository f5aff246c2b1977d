#pragma once

#include <lodestone/view/Snapshot.h>

#include <mrpt/opengl/COpenGLScene.h>

#include <ostream>
#include <string>

namespace lodestone::view {

/** Shows `scene` in MRPT's 3D window until it is closed or q / Esc is pressed. Keys toggle the
 * layers (n nodes, o odometry, l closures, r refused, c cloud, m mesh, t truth, f floor); the mouse
 * orbits, pans and zooms as in every MRPT window. Needs a display. */
void showWindow(const mrpt::opengl::COpenGLScene::Ptr& scene, const ViewCamera& camera,
                const std::string& title, std::ostream& out);

}  // namespace lodestone::view
