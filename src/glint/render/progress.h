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
    /// Ends the bar and prints the total time ("glint: rendered in 0.9 s"), and the samples
    /// per pixel when `samplesPerPixel` > 0 (a render to a time budget: "glint: rendered 96
    /// samples per pixel in 10.0 s").
    void finish(const RenderProgress& p, bool complete, int samplesPerPixel = 0);

  private:
    std::FILE* out_;
    bool terminal_;
    double logInterval_;
    double lastLog_ = 0;
};

/// "1.2 s", "3 min 4 s", ...
std::string formatSeconds(double s);

}  // namespace glint
