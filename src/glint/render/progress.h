#pragma once
/// Render progress on a terminal (one redrawn bar) or a log (occasional plain lines).

#include <cstdio>
#include <string>

#include "glint/render/renderer.h"

namespace glint {

class ProgressReporter {
  public:
    /// Writes to `out`, redrawing one line if `terminal`, else plain lines at most every
    /// `logInterval` seconds.
    ProgressReporter(std::FILE* out, bool terminal, double logInterval = 5.0)
        : out_(out), terminal_(terminal), logInterval_(logInterval) {}

    void update(const RenderProgress& p);
    /// Ends the bar and prints the total time.
    void finish(const RenderProgress& p, bool complete);

  private:
    std::FILE* out_;
    bool terminal_;
    double logInterval_;
    double lastLog_ = 0;
};

/// "1.2 s", "3 min 4 s", ...
std::string formatSeconds(double s);

}  // namespace glint
