#pragma once

#include <lodestone/graphslam/PoseGraph.h>
#include <lodestone/graphslam/gso/PoseGraphSolver.h>
#include <mrpt/poses/CPose2D.h>
#include <mrpt/poses/CPose3D.h>

#include <Eigen/Core>

namespace lodestone::graphslam::relocalization {

/** The pose space a graph is solved in, as the relocalizer's algebra (ClosureAlgebra) needs
 * it: poses, their coordinates (a chart around the identity, in which a closure's covariance
 * is read as the solver reads it), composition, and the closure's covariance. */

/** A ground robot's graph: x, y, yaw (the rest held stiff by the node decider). */
struct PlanarSpace {
    static constexpr int kDof = 3;
    static constexpr int kTranslationDof = 2;
    static constexpr double kChi2999 = kChi2Planar999;
    using Pose = mrpt::poses::CPose2D;
    using Vector = Eigen::Matrix<double, 3, 1>;
    using Matrix = Eigen::Matrix<double, 3, 3>;

    static Pose fromGraph(const mrpt::poses::CPose3D& p);
    static mrpt::poses::CPose3D toGraph(const Pose& p);
    /** x, y, yaw wrapped to (-pi, pi]. */
    static Vector coordinates(const Pose& p);
    static Pose pose(const Vector& v);
    /** A difference of coordinates with its angle wrapped. */
    static Vector wrapped(Vector d);
    static Pose compose(const Pose& a, const Pose& b) { return a + b; }
    static Pose inverse(const Pose& p);
    /** A pose moved by a small step: its coordinates plus the step (x, y, yaw). */
    static Pose perturbed(const Pose& p, const Vector& step) { return pose(coordinates(p) + step); }
    /** The x, y, yaw block of the closure's information, inverted. */
    static Matrix covarianceOf(const Constraint& c);
};

/** A hand-held camera's graph, SE(3): translation x, y, z and the rotation vector (about x, y,
 * z) - the chart of the SE(3) solver's error (Se3RelativePoseCost), to first order. */
struct SpatialSpace {
    static constexpr int kDof = 6;
    static constexpr int kTranslationDof = 3;
    static constexpr double kChi2999 = kChi2Se3999;
    using Pose = mrpt::poses::CPose3D;
    using Vector = Eigen::Matrix<double, 6, 1>;
    using Matrix = Eigen::Matrix<double, 6, 6>;

    static Pose fromGraph(const mrpt::poses::CPose3D& p) { return p; }
    static mrpt::poses::CPose3D toGraph(const Pose& p) { return p; }
    static Vector coordinates(const Pose& p);
    static Pose pose(const Vector& v);
    /** (a rotation vector's difference needs no wrapping near the identity, where the
     * Jacobians are taken) */
    static Vector wrapped(Vector d) { return d; }
    static Pose compose(const Pose& a, const Pose& b) { return a + b; }
    static Pose inverse(const Pose& p);
    /** A pose moved by a small step in its own frame, p (+) pose(step): right-composed, as the
     * solver's error is read, and well-behaved at any rotation (a rotation vector added to a
     * global pose's is not, near half a turn). */
    static Pose perturbed(const Pose& p, const Vector& step) { return p + pose(step); }
    /** MRPT's x, y, z, yaw, pitch, roll information reordered to x, y, z, about x, y, z (as
     * the solver does), inverted. */
    static Matrix covarianceOf(const Constraint& c);
};

}  // namespace lodestone::graphslam::relocalization
