// libFuzzer target: one line of a run's resume journal. Any line is either a
// result whose counts agree with each other or refused with InputError (or a
// JSON parse error); nothing is trusted as written.
#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>

#include "hgridlab/scenes/detail/results.hpp"
#include "hgridlab/base/error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto j = nlohmann::json::parse(data, data + size, nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded() || !j.is_object() || !j.contains("result")) return 0;
  try {
    const hgrid::PointResult r = hgrid::detail::result_from_json(j.at("result"));
    hgrid::detail::check_result(r, 0.2);
  } catch (const hgrid::InputError&) {
  }
  return 0;
}
