#include <lodestone/plot/Colormap.h>
#include <lodestone/view/Palette.h>
#include <lodestone/view/SceneBuilder.h>

#include <mrpt/opengl/CFrustum.h>
#include <mrpt/opengl/CGridPlaneXY.h>
#include <mrpt/opengl/CPointCloudColoured.h>
#include <mrpt/opengl/CSetOfLines.h>
#include <mrpt/opengl/CSetOfTriangles.h>

#include <algorithm>
#include <cmath>
#include <map>

namespace lodestone::view {

namespace {

mrpt::opengl::CSetOfLines::Ptr lines(const std::string& name, const mrpt::img::TColor& colour, float width) {
    auto l = mrpt::opengl::CSetOfLines::Create();
    l->setName(name);
    l->setColor_u8(colour);
    l->setLineWidth(width);
    l->enableAntiAliasing(false);  // (exact colours: a closer is told by its colour)
    return l;
}

void join(mrpt::opengl::CSetOfLines& l, const ViewNode& a, const ViewNode& b) {
    l.appendLine(a.pose.x(), a.pose.y(), a.pose.z(), b.pose.x(), b.pose.y(), b.pose.z());
}

mrpt::opengl::CPointCloudColoured::Ptr nodes(const SceneContent& c) {
    auto cloud = mrpt::opengl::CPointCloudColoured::Create();
    cloud->setName("nodes");
    cloud->setPointSize(4);
    const bool byError = !std::isnan(c.maxError);
    const plot::Colormap errors(0, byError && c.maxError > 0 ? c.maxError : 1);
    for (const auto& n : c.nodes) {
        mrpt::img::TColor colour = segmentColour(n.segment);
        if (byError) {
            const cv::Vec3b bgr = errors(n.error);
            colour = mrpt::img::TColor(bgr[2], bgr[1], bgr[0]);
        }
        cloud->push_back(static_cast<float>(n.pose.x()), static_cast<float>(n.pose.y()),
                         static_cast<float>(n.pose.z()), colour.R / 255.f, colour.G / 255.f,
                         colour.B / 255.f);
    }
    return cloud;
}

/** Each node's mean |B| as a ribbon of points 5 cm below the path (the plots' viridis over the
 * run's range); none without readings. */
mrpt::opengl::CPointCloudColoured::Ptr fieldRibbon(const SceneContent& c) {
    double lo = INFINITY, hi = -INFINITY;
    for (const auto& n : c.nodes)
        if (!std::isnan(n.field)) lo = std::min(lo, n.field), hi = std::max(hi, n.field);
    if (!(lo <= hi)) return nullptr;
    const plot::Colormap scale(lo, hi);
    auto ribbon = mrpt::opengl::CPointCloudColoured::Create();
    ribbon->setName("field");
    ribbon->setPointSize(6);
    for (const auto& n : c.nodes) {
        if (std::isnan(n.field)) continue;
        const cv::Vec3b bgr = scale(n.field);
        ribbon->push_back(static_cast<float>(n.pose.x()), static_cast<float>(n.pose.y()),
                          static_cast<float>(n.pose.z() - 0.05), bgr[2] / 255.f, bgr[1] / 255.f,
                          bgr[0] / 255.f);
    }
    return ribbon;
}

mrpt::opengl::CPointCloudColoured::Ptr cloudOf(const ViewCloud& points) {
    auto cloud = mrpt::opengl::CPointCloudColoured::Create();
    cloud->setName("cloud");
    cloud->setPointSize(1);
    for (std::size_t i = 0; i < points.size(); ++i)
        cloud->push_back(points.xyz[3 * i], points.xyz[3 * i + 1], points.xyz[3 * i + 2],
                         points.rgb[3 * i] / 255.f, points.rgb[3 * i + 1] / 255.f,
                         points.rgb[3 * i + 2] / 255.f);
    return cloud;
}

mrpt::opengl::CSetOfTriangles::Ptr meshOf(const ViewMesh& mesh) {
    auto triangles = mrpt::opengl::CSetOfTriangles::Create();
    triangles->setName("mesh");
    std::vector<mrpt::opengl::TTriangle> all;
    all.reserve(mesh.size());
    for (std::size_t t = 0; t < mesh.size(); ++t) {
        mrpt::opengl::TTriangle tri;
        for (int k = 0; k < 3; ++k) {
            const std::size_t v = static_cast<std::size_t>(mesh.triangles[3 * t + k]);
            auto& p = tri.vertices[k].xyzrgba;
            p.pt = {mesh.xyz[3 * v], mesh.xyz[3 * v + 1], mesh.xyz[3 * v + 2]};
            p.r = mesh.rgb[3 * v];
            p.g = mesh.rgb[3 * v + 1];
            p.b = mesh.rgb[3 * v + 2];
            p.a = 255;
        }
        tri.computeNormals();
        all.push_back(tri);
    }
    triangles->insertTriangles(all.begin(), all.end());
    return triangles;
}

}  // namespace

mrpt::opengl::COpenGLScene::Ptr buildScene(const SceneContent& c, const Layers& layers) {
    auto scene = mrpt::opengl::COpenGLScene::Create();
    if (layers.floor && !c.nodes.empty()) {
        double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300, z = 1e300;
        for (const auto& n : c.nodes) {
            x0 = std::min(x0, n.pose.x()), x1 = std::max(x1, n.pose.x());
            y0 = std::min(y0, n.pose.y()), y1 = std::max(y1, n.pose.y());
            z = std::min(z, n.pose.z());
        }
        auto grid = mrpt::opengl::CGridPlaneXY::Create(std::floor(x0) - 1, std::ceil(x1) + 1,
                                                       std::floor(y0) - 1, std::ceil(y1) + 1, z, 1);
        grid->setName("floor");
        grid->setColor_u8(mrpt::img::TColor(200, 200, 200));
        scene->insert(grid);
    }
    if (layers.mesh && c.mesh.size() > 0) {
        scene->insert(meshOf(c.mesh));
    } else if (layers.cloud && c.cloud.size() > 0) {
        scene->insert(cloudOf(c.cloud));
    }
    if (layers.truth && !c.truth.empty()) {
        auto truth = lines("truth", truthColour(), 1);
        for (std::size_t i = 1; i < c.truth.size(); ++i) truth->appendLine(c.truth[i - 1], c.truth[i]);
        scene->insert(truth);
    }
    auto odometry = lines("odometry", odometryColour(), 1);
    auto refused = lines("refused", refusedColour(), 2);
    std::map<std::string, mrpt::opengl::CSetOfLines::Ptr> closures;
    for (const auto& e : c.edges) {
        const ViewNode* a = c.node(e.from);
        const ViewNode* b = c.node(e.to);
        if (!a || !b) continue;
        switch (e.kind) {
            case EdgeKind::Odometry: join(*odometry, *a, *b); break;
            case EdgeKind::RefusedClosure: join(*refused, *a, *b); break;
            case EdgeKind::Closure: {
                auto& l = closures[e.closer];
                if (!l) l = lines("closures/" + e.closer, closerColour(e.closer), 2);
                join(*l, *a, *b);
                break;
            }
        }
    }
    if (layers.odometry && !odometry->empty()) scene->insert(odometry);
    if (layers.closures)
        for (auto& [closer, l] : closures) scene->insert(l);
    if (layers.refused && !refused->empty()) scene->insert(refused);
    if (layers.field)
        if (auto ribbon = fieldRibbon(c)) scene->insert(ribbon);
    if (layers.nodes && !c.nodes.empty()) scene->insert(nodes(c));
    if (layers.current && c.hasCurrent) {
        // (a camera's view cone along the robot's +x, as MRPT's frustum looks)
        auto frustum = mrpt::opengl::CFrustum::Create(0.05f, 0.6f, 60.f, 45.f, 1.f, true, false);
        frustum->setName("current");
        frustum->setPose(c.current);
        frustum->setColor_u8(mrpt::img::TColor(255, 255, 255));
        scene->insert(frustum);
    }
    for (std::size_t i = 0; i < c.overlay.size(); ++i) {
        mrpt::opengl::TFontParams font;
        font.color = mrpt::img::TColorf(1, 1, 1);
        font.vfont_scale = 14;
        scene->getViewport()->addTextMessage(8, -20.0 - 18.0 * double(i), c.overlay[i], i, font);
    }
    return scene;
}

std::vector<std::string> layerNames(const mrpt::opengl::COpenGLScene& scene) {
    std::vector<std::string> names;
    for (const auto& object : *scene.getViewport()) names.push_back(object->getName());
    return names;
}

}  // namespace lodestone::view
