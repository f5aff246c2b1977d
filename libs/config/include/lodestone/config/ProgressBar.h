#pragma once

#include <chrono>
#include <ostream>

namespace lodestone::config {

/** Progress of a long run with rate and ETA. On a terminal one line redrawn in place (at most
 * five times a second); otherwise a plain line every tenth of the way, so logs stay readable;
 * `quiet` prints nothing. */
class ProgressBar {
  public:
    ProgressBar(std::ostream& out, bool terminal, bool quiet);
    /** `fraction` of the input done (0..1), `dataSeconds` of sensor time processed. */
    void update(double fraction, double dataSeconds);
    /** Ends the line (terminal) and prints the final rate. */
    void finish(double dataSeconds);

  private:
    std::string line(double fraction, double dataSeconds, double elapsed) const;

    std::ostream& out_;
    bool terminal_, quiet_;
    std::chrono::steady_clock::time_point start_, last_draw_;
    int last_tenth_{0};
    bool drawn_{false};
};

}  // namespace lodestone::config
