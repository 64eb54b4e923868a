// Scene files (app/scene/SceneParse.cpp): any text gives a scene or a SceneError.
#include "scene/Scene.hpp"

#include <cstddef>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    umbra::scene::parseScene(std::string(reinterpret_cast<const char*>(data), size), "fuzz.json");
  } catch (const umbra::scene::SceneError&) {
  }
  return 0;
}
