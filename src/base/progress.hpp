// The one progress reporter of long work (packing generation, scene runs, DPM
// runs): stderr, percentage, rate, ETA. On a terminal the line is redrawn in
// place; otherwise (a log file, CI) a line is printed every few seconds.
#pragma once
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <mutex>
#include <string>

#include "hgridlab/base/clock.hpp"

namespace hgrid {

class Progress {
 public:
  /// `what` names the work; `unit` names what count() counts ("points").
  Progress(bool enabled, std::string what, std::string unit = "")
      : on_(enabled), tty_(enabled && ::isatty(2) == 1), what_(std::move(what)), unit_(std::move(unit)) {}
  ~Progress() { finish(); }
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  /// fraction in [0, 1]; extra is appended verbatim. Rate-limited.
  void update(double fraction, const std::string& extra = "") { report(fraction, -1, extra); }

  /// done of total units: the rate is in units per second.
  void count(double done, double total, const std::string& extra = "") {
    report(total > 0 ? done / total : 1.0, done, extra);
  }

  /// Ends a redrawn line (a terminal); called by the destructor.
  void finish() {
    std::lock_guard<std::mutex> lock(mu_);
    if (tty_ && drawn_) std::fputc('\n', stderr);
    drawn_ = false;
  }

  double elapsed() const { return seconds_since(start_); }

 private:
  void report(double fraction, double done, const std::string& extra) {
    if (!on_) return;
    std::lock_guard<std::mutex> lock(mu_);
    const auto now = Clock::now();
    if (now - last_ < (tty_ ? std::chrono::milliseconds(200) : std::chrono::milliseconds(2000))) return;
    last_ = now;
    const double t = std::chrono::duration<double>(now - start_).count();
    const double eta = fraction > 1e-9 ? t * (1 - fraction) / fraction : 0.0;
    char rate[64] = "";
    if (done >= 0 && t > 0) std::snprintf(rate, sizeof rate, ", %.3g %s/s", done / t, unit_.c_str());
    std::fprintf(stderr, "%s  %s: %5.1f %%%s  %s%s%.0f s elapsed, ETA %.0f s%s", tty_ ? "\r" : "", what_.c_str(),
                 100 * fraction, rate, extra.c_str(), extra.empty() ? "" : "  ", t, eta, tty_ ? "\033[K" : "\n");
    std::fflush(stderr);
    drawn_ = true;
  }

  bool on_, tty_;
  bool drawn_ = false;
  std::string what_, unit_;
  std::mutex mu_;
  Clock::time_point start_ = Clock::now(), last_ = Clock::now();
};

}  // namespace hgrid
