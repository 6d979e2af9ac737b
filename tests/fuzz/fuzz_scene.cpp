// libFuzzer target: the scene reader (TOML), at every scale. Any input gives
// a scene or an InputError; the packings of a scene are not generated.
#include <cstddef>
#include <cstdint>
#include <string>

#include "hgridlab/scenes/scene.hpp"
#include "hgridlab/base/error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  for (const char* scale : {"smoke", "default", "paper"}) {
    try {
      hgrid::load_scene_text(text, scale, "fuzz.toml");
    } catch (const hgrid::InputError&) {
    }
  }
  return 0;
}
