// Wall-clock seconds of a piece of work: the one clock the library times work
// with (progress lines, measurements, DPM steps, scene runs).
#pragma once
#include <chrono>

namespace hgrid {

using Clock = std::chrono::steady_clock;

/// Seconds from t to now.
inline double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

}  // namespace hgrid
