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
  std::string note;              // why a stored calibration was not used (empty: none stored, or used)
};

/// `given` (a number >= 0, or "auto": a missing or unreadable calibration is
/// an InputError naming `field`) when not empty; else the stored calibration
/// when its file exists and reads; else kPaperK, with `note` saying why a
/// calibration file that exists was not used (an old format, say).
KChoice choose_K(const std::string& given, const std::string& field = "K");

}  // namespace hgrid
