#include <lodestone/graphslam/SlamEngine.h>
#include <lodestone/view/EngineSnapshot.h>
#include <lodestone/view/LiveView.h>
#include <lodestone/view/SceneBuilder.h>
#include <lodestone/view/Snapshot.h>

#include <mrpt/gui/CDisplayWindow3D.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <map>

namespace lodestone::view {

namespace {

double wallSeconds() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

/** The status lines over the view. */
std::vector<std::string> overlayOf(const graphslam::SlamEngine& engine, const SceneContent& c,
                                   const LiveView::Status& status, bool paused, bool finished) {
    char line[160];
    std::vector<std::string> lines;
    std::snprintf(line, sizeof line, "t %.1f s   %.2fx real time%s", status.dataSeconds,
                  status.realTimeFactor, finished ? "   (run finished)" : "");
    lines.emplace_back(line);
    std::size_t keyframes = 0;
    for (const auto& n : c.nodes) keyframes += n.keyframe;
    std::snprintf(line, sizeof line, "nodes %zu   keyframes %zu   segments %d", c.nodes.size(), keyframes,
                  c.segments());
    lines.emplace_back(line);
    std::map<std::string, std::size_t> kept;
    std::size_t refused = 0;
    for (const auto& lc : engine.optimizer().loopClosures()) lc.rejected ? ++refused : ++kept[lc.source];
    std::string closures = "closures:";
    for (const auto& [closer, n] : kept) closures += " " + closer + " " + std::to_string(n);
    closures += "   refused " + std::to_string(refused);
    lines.push_back(closures);
    if (!status.tracking.empty()) lines.push_back("tracking: " + status.tracking);
    if (!c.nodes.empty() && c.nodes.back().segment != c.nodes.front().segment)
        lines.emplace_back("relocating: the current segment is not joined to the map yet");
    if (engine.stats().relocations > 0)
        lines.push_back("relocations " + std::to_string(engine.stats().relocations));
    if (paused) lines.emplace_back("PAUSED: space resumes, s steps one node");
    return lines;
}

}  // namespace

struct LiveView::Window {
    mrpt::gui::CDisplayWindow3D::Ptr window;
    Layers layers;
    bool follow{true};
    /** When each refused closure was first drawn [wall s]: shown for a while, then left out
     * (the window would fill with them otherwise; the report lists them all). */
    std::map<std::pair<std::uint64_t, std::uint64_t>, double> refusedSince;
    static constexpr double kRefusedSeconds = 5;

    void forgetOldRefusals(SceneContent& c) {
        const double now = wallSeconds();
        auto& edges = c.edges;
        edges.erase(std::remove_if(edges.begin(), edges.end(),
                                   [&](const ViewEdge& e) {
                                       if (e.kind != EdgeKind::RefusedClosure) return false;
                                       const auto it = refusedSince.emplace(std::make_pair(e.from, e.to), now).first;
                                       return now - it->second > kRefusedSeconds;
                                   }),
                    edges.end());
    }
};

std::unique_ptr<LiveView> LiveView::open(std::ostream& warn, double period) {
    if (!std::getenv("DISPLAY")) {
        warn << "--view: no display (DISPLAY is not set): the run goes on without the view\n";
        return nullptr;
    }
    std::unique_ptr<LiveView> view(new LiveView(period));
    try {
        view->window_ = std::make_unique<Window>();
        view->window_->window = mrpt::gui::CDisplayWindow3D::Create("Lodestone", 1280, 960);
    } catch (const std::exception& e) {
        warn << "--view: the window could not be opened (" << e.what() << "): the run goes on without it\n";
        return nullptr;
    }
    view->drawer_ = std::thread([v = view.get()] { v->drawLoop(); });
    return view;
}

LiveView::LiveView(double period) : period_(period) {}

LiveView::~LiveView() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        closing_ = true;
        paused_ = false;
    }
    changed_.notify_all();
    if (drawer_.joinable()) drawer_.join();
}

std::size_t LiveView::snapshotsDrawn() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return drawn_;
}

bool LiveView::isOpen() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return !closed_;
}

void LiveView::publish(const graphslam::SlamEngine& engine, const Status& status) {
    // (copied on the run's thread: the view's thread never touches the engine)
    bool paused = false;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        paused = paused_ || step_;
    }
    auto snapshot = std::make_unique<SceneContent>(snapshotOf(engine));
    snapshot->overlay = overlayOf(engine, *snapshot, status, paused, false);
    std::lock_guard<std::mutex> lock(mutex_);
    pending_ = std::move(snapshot);
    changed_.notify_all();
}

bool LiveView::wantsOffer() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return !closed_ && (paused_ || step_ || wallSeconds() - lastOffer_ >= period_);
}

void LiveView::offer(const graphslam::SlamEngine& engine, const Status& status) {
    std::unique_lock<std::mutex> lock(mutex_);
    if (closed_) return;
    const double now = wallSeconds();
    bool due = now - lastOffer_ >= period_;
    if (step_ && engine.graph().nodes.size() > nodesAtStep_) {
        step_ = false;
        paused_ = true;
        due = true;
    }
    if (due) {
        lastOffer_ = now;
        lock.unlock();
        publish(engine, status);
        lock.lock();
    }
    while (paused_ && !closed_ && !closing_) {
        changed_.wait(lock);
        if (step_ && !paused_) nodesAtStep_ = engine.graph().nodes.size();
    }
}

void LiveView::finish(const graphslam::SlamEngine& engine, const Status& status, bool keepOpen) {
    auto snapshot = std::make_unique<SceneContent>(snapshotOf(engine));
    snapshot->overlay = overlayOf(engine, *snapshot, status, false, true);
    std::unique_lock<std::mutex> lock(mutex_);
    if (closed_) return;
    pending_ = std::move(snapshot);
    paused_ = step_ = false;
    if (!keepOpen) closing_ = true;
    changed_.notify_all();
    // Closing: the drawer draws what is pending first, then ends.
    changed_.wait(lock, [&] { return closed_; });
}

void LiveView::drawLoop() {
    auto& w = *window_;
    static const std::map<int, bool Layers::*> toggles{
        {'n', &Layers::nodes},  {'o', &Layers::odometry}, {'l', &Layers::closures},
        {'r', &Layers::refused}, {'c', &Layers::cloud},   {'t', &Layers::truth},
        {'f', &Layers::floor},  {'b', &Layers::field},    {'k', &Layers::current}};
    SceneContent shown;
    bool redraw = false, framed = false;
    for (;;) {
        std::unique_ptr<SceneContent> next;
        {
            std::unique_lock<std::mutex> lock(mutex_);
            changed_.wait_for(lock, std::chrono::milliseconds(40), [&] { return pending_ || closing_; });
            if (!w.window->isOpen()) {
                closed_ = true;
                paused_ = false;
                changed_.notify_all();
                return;
            }
            if (!pending_ && closing_) {
                closed_ = true;
                changed_.notify_all();
                return;
            }
            next = std::move(pending_);
        }
        while (w.window->keyHit()) {
            int key = w.window->getPushedKey();
            if (key >= 'A' && key <= 'Z') key += 'a' - 'A';
            std::lock_guard<std::mutex> lock(mutex_);
            if (key == 'q' || key == 27) {
                closed_ = true;
                paused_ = false;
                changed_.notify_all();
                return;
            } else if (key == ' ') {
                paused_ = !paused_;
                step_ = false;
            } else if (key == 's' && paused_) {
                paused_ = false;
                step_ = true;
            } else if (key == 'v') {
                w.follow = !w.follow;
            } else if (const auto it = toggles.find(key); it != toggles.end()) {
                w.layers.*(it->second) = !(w.layers.*(it->second));
                redraw = true;
            }
            changed_.notify_all();
        }
        if (next) {
            shown = std::move(*next);
            w.forgetOldRefusals(shown);
            redraw = true;
        }
        if (!redraw) continue;
        redraw = false;
        const auto scene = buildScene(shown, w.layers);
        {
            auto& s = w.window->get3DSceneAndLock();
            s = scene;
            w.window->unlockAccess3DScene();
        }
        if (!framed || (w.follow && shown.hasCurrent)) {
            const ViewCamera camera = framing(shown);
            const double* at = camera.pointingAt;
            if (w.follow && shown.hasCurrent) {
                w.window->setCameraPointingToPoint(static_cast<float>(shown.current.x()),
                                                   static_cast<float>(shown.current.y()),
                                                   static_cast<float>(shown.current.z()));
            } else {
                w.window->setCameraPointingToPoint(static_cast<float>(at[0]), static_cast<float>(at[1]),
                                                   static_cast<float>(at[2]));
            }
            if (!framed) {
                w.window->setCameraZoom(static_cast<float>(camera.distance));
                w.window->setCameraAzimuthDeg(static_cast<float>(camera.azimuthDeg));
                w.window->setCameraElevationDeg(static_cast<float>(camera.elevationDeg));
                framed = true;
            }
        }
        w.window->repaint();
        std::lock_guard<std::mutex> lock(mutex_);
        ++drawn_;
        changed_.notify_all();
    }
}

}  // namespace lodestone::view
