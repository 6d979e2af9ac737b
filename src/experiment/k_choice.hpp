// Which K (cell access time over overlap test time) a recommendation uses:
// the one given, else this machine's stored calibration, else the paper's.
#pragma once
#include <string>

namespace hgrid {

/// The paper's K (Krijgsman et al. 2014, Sect. 5).
inline constexpr double kPaperK = 0.2;

enum class KSource { given, calibration, paper };
/// "given" | "calibration" | "paper".
const char* to_string(KSource s);

struct KChoice {
  double K = kPaperK;
  KSource source = KSource::paper;
  std::string calibration_path;  // where a calibration is (or would be) stored
};

/// `given` (a number >= 0, or "auto") when not empty; else the stored
/// calibration when its file exists (a corrupt one is an InputError naming
/// `field`); else kPaperK.
KChoice choose_K(const std::string& given, const std::string& field = "K");

}  // namespace hgrid
