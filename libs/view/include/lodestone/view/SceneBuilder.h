#pragma once

#include <lodestone/view/SceneContent.h>

#include <mrpt/opengl/COpenGLScene.h>

#include <string>

namespace lodestone::view {

/** Which layers a scene holds. Each layer is one named object of the scene ("nodes",
 * "odometry", "closures/<closer>", "refused", "cloud", "truth", "floor", "field",
 * "current", "mesh"), so a window can toggle it by name. The mesh, where there is one, is
 * drawn instead of the cloud. */
struct Layers {
    bool nodes{true}, odometry{true}, closures{true}, refused{true}, cloud{true}, truth{true},
        floor{true}, field{true}, current{true}, mesh{true};
};

/** The scene of `content`: nodes coloured by segment (by their error against the truth where
 * there is one: the plots' viridis from 0 to the largest), odometry edges, kept closures in
 * their closer's colour, refused ones in red, the cloud, the truth's path in grey, a 1 m grid
 * at the lowest node's height, the nodes' |B| as a ribbon below the path, the current pose's
 * view cone and the overlay's lines at the top left. */
mrpt::opengl::COpenGLScene::Ptr buildScene(const SceneContent& content, const Layers& layers = {});

/** The names of the scene's layer objects, in drawing order. */
std::vector<std::string> layerNames(const mrpt::opengl::COpenGLScene& scene);

}  // namespace lodestone::view
