#include <lodestone/sim/MotionPlan.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace lodestone::sim {

namespace {
double wrapAngle(double a) { return std::atan2(std::sin(a), std::cos(a)); }

double smoothstep(double s) { return s * s * (3 - 2 * s); }

// The planner's state while it walks the loop.
struct Cursor {
    RobotPose pose;
    double t{0};
    std::size_t legsDone{0};   // legs driven towards the lap count
    std::size_t nextWaypoint;  // index of the waypoint being driven to
};
}  // namespace

void MotionPlan::append(MotionSegment s) {
    if (s.t1 <= s.t0) return;
    Eigen::Vector2d wheels =
        wheel_at_start_.empty() ? Eigen::Vector2d::Zero() : Eigen::Vector2d(wheel_at_start_.back());
    if (!segments_.empty()) {
        const auto& prev = segments_.back();
        const double r = params_.wheelRadius, half = params_.wheelBase / 2;
        if (prev.kind == MotionSegment::Kind::Drive) {
            const double d = std::hypot(prev.end.x - prev.start.x, prev.end.y - prev.start.y);
            wheels += Eigen::Vector2d(d / r, d / r);
        } else if (prev.kind == MotionSegment::Kind::Rotate) {
            const double dyaw = prev.end.yaw - prev.start.yaw;
            wheels += Eigen::Vector2d(-half * dyaw / r, half * dyaw / r);
        }
    }
    segments_.push_back(s);
    wheel_at_start_.push_back(wheels);
}

MotionPlan::MotionPlan(
    const Params& params, const std::vector<KidnapSpec>& kidnapsIn,
    const std::function<bool(const Eigen::Vector2d&, const Eigen::Vector2d&)>& reachable)
    : params_(params) {
    const auto& wp = params_.waypoints;
    if (wp.size() < 2) throw std::invalid_argument("the path needs at least 2 waypoints");
    if (params_.speed <= 0 || params_.turnRate <= 0) {
        throw std::invalid_argument("speed and turn rate must be positive");
    }
    std::vector<KidnapSpec> kidnaps = kidnapsIn;
    std::sort(kidnaps.begin(), kidnaps.end(),
              [](const auto& a, const auto& b) { return a.start < b.start; });
    std::size_t nextKidnap = 0;

    Cursor c;
    c.pose = {wp[0].x(), wp[0].y(), std::atan2(wp[1].y() - wp[0].y(), wp[1].x() - wp[0].x()), 0};
    c.nextWaypoint = 1;
    const std::size_t totalLegs = static_cast<std::size_t>(std::max(0, params_.laps)) * wp.size();

    // Appends motion, unless a kidnap starts inside it: then the motion is cut there, the
    // carry appended, and true returned (the caller re-plans from the put-down).
    const auto move = [&](MotionSegment s) -> bool {
        if (nextKidnap < kidnaps.size() && kidnaps[nextKidnap].start < s.t1) {
            const KidnapSpec& k = kidnaps[nextKidnap++];
            const double cut = std::max(s.t0, k.start);
            MotionSegment part = s;
            part.t1 = cut;
            part.end = poseOnSegment(s, cut);
            // poseOnSegment wraps the heading, but the segment interpolates from its start's
            // unwrapped heading (turns accumulate over laps): keep the cut end on that branch,
            // or a drive cut by a kidnap spins through every turn of the laps before it.
            part.end.yaw = s.start.yaw + wrapAngle(part.end.yaw - s.start.yaw);
            append(part);
            MotionSegment carry;
            carry.kind = MotionSegment::Kind::Carry;
            carry.t0 = cut;
            carry.t1 = cut + k.duration;
            carry.start = part.end;
            carry.end = k.putDown;
            carry.liftHeight = k.liftHeight;
            append(carry);
            c.pose = k.putDown;
            c.t = carry.t1;
            // Resume at the nearest waypoint reachable in a straight line.
            double best = std::numeric_limits<double>::infinity();
            std::size_t bestIndex = wp.size();
            for (std::size_t i = 0; i < wp.size(); ++i) {
                const double d = std::hypot(wp[i].x() - c.pose.x, wp[i].y() - c.pose.y);
                if (d < best && reachable(Eigen::Vector2d(c.pose.x, c.pose.y), wp[i])) {
                    best = d;
                    bestIndex = i;
                }
            }
            if (bestIndex == wp.size()) {
                throw std::invalid_argument(k.name +
                                            ": no waypoint can be reached in a straight "
                                            "line from the put-down pose");
            }
            c.nextWaypoint = bestIndex;
            return true;
        }
        append(s);
        c.pose = s.end;
        c.t = s.t1;
        return false;
    };

    bool approaching = false;  // driving to the resume waypoint after a put-down
    while (c.legsDone < totalLegs || approaching) {
        const Eigen::Vector2d target = wp[c.nextWaypoint];
        const double dx = target.x() - c.pose.x, dy = target.y() - c.pose.y;
        const double distance = std::hypot(dx, dy);
        MotionSegment rot;
        rot.kind = MotionSegment::Kind::Rotate;
        rot.start = c.pose;
        rot.end = c.pose;
        if (distance > 1e-9) {
            rot.end.yaw = c.pose.yaw + wrapAngle(std::atan2(dy, dx) - c.pose.yaw);
        }
        rot.t0 = c.t;
        rot.t1 = c.t + std::abs(rot.end.yaw - rot.start.yaw) / params_.turnRate;
        if (move(rot)) {
            approaching = true;
            continue;
        }
        MotionSegment drive;
        drive.kind = MotionSegment::Kind::Drive;
        drive.start = c.pose;
        drive.end = c.pose;
        drive.end.x = target.x();
        drive.end.y = target.y();
        drive.t0 = c.t;
        drive.t1 = c.t + distance / params_.speed;
        if (move(drive)) {
            approaching = true;
            continue;
        }
        if (approaching) {
            approaching = false;
        } else {
            ++c.legsDone;
        }
        c.nextWaypoint = (c.nextWaypoint + 1) % wp.size();
    }
    // Kidnaps after the last lap still happen: the robot waits, then is carried.
    while (nextKidnap < kidnaps.size()) {
        MotionSegment wait;
        wait.kind = MotionSegment::Kind::Wait;
        wait.start = wait.end = c.pose;
        wait.t0 = c.t;
        wait.t1 = std::max(c.t, kidnaps[nextKidnap].start) + 1e-3;
        move(wait);
    }
    MotionSegment rest;  // a short stop at the end, so the last sensor samples see it still
    rest.kind = MotionSegment::Kind::Wait;
    rest.start = rest.end = c.pose;
    rest.t0 = c.t;
    rest.t1 = c.t + 1.0;
    append(rest);
}

const MotionSegment& MotionPlan::segmentAt(double t) const {
    auto it = std::upper_bound(segments_.begin(), segments_.end(), t,
                               [](double time, const MotionSegment& s) { return time < s.t1; });
    if (it == segments_.end()) return segments_.back();
    return *it;
}

RobotPose MotionPlan::poseAt(double t) const {
    if (segments_.empty()) return {};
    return poseOnSegment(segmentAt(t), t);
}

RobotPose poseOnSegment(const MotionSegment& s, double t) {
    const double span = s.t1 - s.t0;
    const double a = span > 0 ? std::clamp((t - s.t0) / span, 0.0, 1.0) : 1.0;
    RobotPose p = s.start;
    switch (s.kind) {
        case MotionSegment::Kind::Wait:
            break;
        case MotionSegment::Kind::Rotate:
        case MotionSegment::Kind::Drive:
            p.x = s.start.x + a * (s.end.x - s.start.x);
            p.y = s.start.y + a * (s.end.y - s.start.y);
            p.yaw = s.start.yaw + a * (s.end.yaw - s.start.yaw);
            break;
        case MotionSegment::Kind::Carry: {
            const double b = smoothstep(a);
            p.x = s.start.x + b * (s.end.x - s.start.x);
            p.y = s.start.y + b * (s.end.y - s.start.y);
            p.yaw = s.start.yaw + b * wrapAngle(s.end.yaw - s.start.yaw);
            p.z = s.liftHeight * std::sin(M_PI * a);
        } break;
    }
    p.yaw = wrapAngle(p.yaw);
    return p;
}

Eigen::Vector2d MotionPlan::wheelAnglesAt(double t) const {
    if (segments_.empty()) return Eigen::Vector2d::Zero();
    const MotionSegment& s = segmentAt(t);
    const std::size_t i = static_cast<std::size_t>(&s - segments_.data());
    Eigen::Vector2d w = wheel_at_start_[i];
    const double span = s.t1 - s.t0;
    const double a = span > 0 ? std::clamp((t - s.t0) / span, 0.0, 1.0) : 1.0;
    const double r = params_.wheelRadius, half = params_.wheelBase / 2;
    if (s.kind == MotionSegment::Kind::Drive) {
        const double d = a * std::hypot(s.end.x - s.start.x, s.end.y - s.start.y);
        w += Eigen::Vector2d(d / r, d / r);
    } else if (s.kind == MotionSegment::Kind::Rotate) {
        const double dyaw = a * (s.end.yaw - s.start.yaw);
        w += Eigen::Vector2d(-half * dyaw / r, half * dyaw / r);
    }
    return w;
}

Eigen::Vector2d MotionPlan::velocityAt(double t) const {
    if (segments_.empty()) return Eigen::Vector2d::Zero();
    const MotionSegment& s = segmentAt(t);
    const double span = s.t1 - s.t0;
    if (span <= 0 || t < s.t0 || t > s.t1) return Eigen::Vector2d::Zero();
    if (s.kind == MotionSegment::Kind::Drive) return {params_.speed, 0};
    if (s.kind == MotionSegment::Kind::Rotate) return {0, (s.end.yaw - s.start.yaw) / span};
    return Eigen::Vector2d::Zero();
}

bool MotionPlan::liftedAt(double t) const {
    if (segments_.empty()) return false;
    const MotionSegment& s = segmentAt(t);
    return s.kind == MotionSegment::Kind::Carry && t >= s.t0 && t < s.t1;
}

}  // namespace lodestone::sim
