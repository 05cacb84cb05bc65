#include "glint/render/progress.h"

#include <cmath>
#include <string>

namespace glint {

std::string formatSeconds(double s) {
    char buf[64];
    if (s < 60)
        std::snprintf(buf, sizeof buf, "%.1f s", s);
    else if (s < 3600)
        std::snprintf(buf, sizeof buf, "%d min %02d s", int(s) / 60, int(s) % 60);
    else
        std::snprintf(buf, sizeof buf, "%d h %02d min", int(s) / 3600, int(s) / 60 % 60);
    return buf;
}

void ProgressReporter::update(const RenderProgress& p) {
    double f = p.fraction();
    std::string eta = f > 0 ? formatSeconds(p.seconds * (1 - f) / f) : std::string("?");
    if (terminal_) {
        constexpr int kWidth = 30;
        int filled = static_cast<int>(f * kWidth);
        std::string bar(filled, '=');
        if (filled < kWidth) bar += '>' + std::string(kWidth - filled - 1, ' ');
        std::fprintf(out_, "\rRendering [%s] %3d%%  %s  ETA %s\x1b[K", bar.c_str(),
                     static_cast<int>(f * 100), formatSeconds(p.seconds).c_str(), eta.c_str());
        std::fflush(out_);
    } else if (p.seconds - lastLog_ >= logInterval_) {
        lastLog_ = p.seconds;
        std::fprintf(out_, "glint: rendering %d%%, %s elapsed, about %s left\n",
                     static_cast<int>(f * 100), formatSeconds(p.seconds).c_str(), eta.c_str());
        std::fflush(out_);
    }
}

void ProgressReporter::finish(const RenderProgress& p, bool complete, int samplesPerPixel) {
    if (terminal_) std::fprintf(out_, "\r\x1b[K");
    char samples[64] = "";
    if (samplesPerPixel > 0)
        std::snprintf(samples, sizeof samples, " %d sample%s per pixel", samplesPerPixel,
                      samplesPerPixel == 1 ? "" : "s");
    std::fprintf(out_, "glint: %s%s in %s\n", complete ? "rendered" : "stopped", samples,
                 formatSeconds(p.seconds).c_str());
    std::fflush(out_);
}

}  // namespace glint
