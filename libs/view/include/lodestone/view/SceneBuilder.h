#pragma once

#include <lodestone/view/SceneContent.h>

#include <mrpt/opengl/COpenGLScene.h>

#include <string>

namespace lodestone::view {

/** Which layers a scene holds. Each layer is one named object of the scene ("nodes",
 * "odometry", "closures/<closer>", "refused", "cloud", "truth", "floor"), so a window can
 * toggle it by name. */
struct Layers {
    bool nodes{true}, odometry{true}, closures{true}, refused{true}, cloud{true}, truth{true},
        floor{true};
};

/** The scene of `content`: nodes coloured by segment (by their error against the truth where
 * there is one: the plots' viridis from 0 to the largest), odometry edges, kept closures in
 * their closer's colour, refused ones in red, the cloud, the truth's path in grey and a 1 m
 * grid at the lowest node's height. */
mrpt::opengl::COpenGLScene::Ptr buildScene(const SceneContent& content, const Layers& layers = {});

/** The names of the scene's layer objects, in drawing order. */
std::vector<std::string> layerNames(const mrpt::opengl::COpenGLScene& scene);

}  // namespace lodestone::view
