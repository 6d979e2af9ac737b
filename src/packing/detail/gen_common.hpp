// Shared pieces of the packing generators: the random stream, progress lines.
#pragma once
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <random>
#include <string>

namespace hgrid::detail {

/// 53 random bits in [0, 1): the same stream on every platform.
class GenRng {
 public:
  explicit GenRng(std::uint64_t seed) : eng_(seed) {}
  double uniform() { return static_cast<double>(eng_() >> 11) * 0x1.0p-53; }
  std::uint64_t bits() { return eng_(); }

 private:
  std::mt19937_64 eng_;
};

/// Volume of the unit d-ball.
inline double unit_ball(int d) { return d == 2 ? 3.14159265358979323846 : 4.0 * 3.14159265358979323846 / 3.0; }

/// Rate-limited progress lines on stderr ("what: done/total ...  ETA").
class Progress {
 public:
  Progress(bool enabled, std::string what) : on_(enabled), what_(std::move(what)) {}
  /// fraction in [0, 1]; extra is appended verbatim.
  void update(double fraction, const std::string& extra) {
    if (!on_) return;
    const auto now = Clock::now();
    if (now - last_ < std::chrono::seconds(2)) return;
    last_ = now;
    const double t = std::chrono::duration<double>(now - start_).count();
    const double eta = fraction > 1e-9 ? t * (1 - fraction) / fraction : 0.0;
    std::fprintf(stderr, "  %s: %5.1f %%  %s  %.0f s elapsed, ETA %.0f s\n", what_.c_str(), 100 * fraction,
                 extra.c_str(), t, eta);
  }
  double elapsed() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }

 private:
  using Clock = std::chrono::steady_clock;
  bool on_;
  std::string what_;
  Clock::time_point start_ = Clock::now(), last_ = Clock::now();
};

}  // namespace hgrid::detail
