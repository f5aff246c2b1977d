#pragma once

#include <lodestone/view/SceneContent.h>

#include <condition_variable>
#include <memory>
#include <mutex>
#include <ostream>
#include <string>
#include <thread>

namespace lodestone::graphslam {
class SlamEngine;
}

namespace lodestone::view {

/** The run as it goes in MRPT's 3D window (lodestone-slam --view, lodestone-grab --slam
 * --view). The run's thread offers the engine after each observation; at most every
 * `period` seconds of wall time a snapshot is copied (EngineSnapshot) and handed to the view's
 * own thread, which builds the scene and draws it - the run never waits for drawing. A
 * refused closure is drawn for 5 s of wall time after it first shows, then left out. Keys:
 * space pauses the run (offline: the engine waits in offer()), s steps one node while paused,
 * v follows the robot or frees the camera, n o l r c t f b k toggle nodes, odometry,
 * closures, refused, cloud, truth, floor, the field ribbon and the current pose; q closes
 * the window (the run goes on). */
class LiveView {
  public:
    struct Status {
        double dataSeconds{0};     ///< [s] of data processed
        double realTimeFactor{0};  ///< data seconds per wall second
        std::string tracking;      ///< the node decider's state, where it says
    };

    /** Opens the window, or returns nullptr after saying why on `warn` (no display). */
    static std::unique_ptr<LiveView> open(std::ostream& warn, double period = 0.25);
    ~LiveView();
    LiveView(const LiveView&) = delete;
    LiveView& operator=(const LiveView&) = delete;

    /** Whether offer() has anything to do now (a snapshot due, or paused or stepping): lets the
     * run skip building a Status for the observations in between. */
    bool wantsOffer() const;
    /** From the run's thread, after an observation: a snapshot when one is due (or the graph
     * gained a node while stepping); waits here while paused. Cheap when none is due. */
    void offer(const graphslam::SlamEngine& engine, const Status& status);
    /** The run is over: the last snapshot is drawn; the window stays until closed if
     * `keepOpen`, else it closes now. */
    void finish(const graphslam::SlamEngine& engine, const Status& status, bool keepOpen);

    std::size_t snapshotsDrawn() const;
    bool isOpen() const;

  private:
    explicit LiveView(double period);
    void publish(const graphslam::SlamEngine& engine, const Status& status);
    void drawLoop();

    struct Window;
    std::unique_ptr<Window> window_;
    double period_;
    double lastOffer_{-1e300};
    std::size_t nodesAtStep_{0};
    mutable std::mutex mutex_;
    std::condition_variable changed_;
    std::unique_ptr<SceneContent> pending_;  // the latest snapshot not drawn yet
    std::size_t drawn_{0};
    bool paused_{false}, step_{false}, closing_{false}, closed_{false};
    std::thread drawer_;
};

}  // namespace lodestone::view
