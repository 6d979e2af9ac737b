#include "hgridlab/calibration/k_choice.hpp"

#include <filesystem>

#include "hgridlab/calibration/calibration.hpp"
#include "hgridlab/base/error.hpp"

namespace hgrid {

const char* to_string(KSource s) {
  switch (s) {
    case KSource::given: return "given";
    case KSource::calibration: return "calibration";
    case KSource::paper: return "paper";
  }
  return "?";
}

KChoice choose_K(const std::string& given, const std::string& field) {
  KChoice c;
  c.calibration_path = calibration_path();
  if (!given.empty()) {
    c.K = resolve_K(given, field);
    c.source = given == "auto" ? KSource::calibration : KSource::given;
  } else if (std::error_code ec; std::filesystem::exists(c.calibration_path, ec)) {
    try {
      c.K = calibrated_K(field);
      c.source = KSource::calibration;
    } catch (const InputError& e) {
      c.note = e.what();
    }
  }
  return c;
}

}  // namespace hgrid
