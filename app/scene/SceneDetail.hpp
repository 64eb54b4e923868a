#pragma once
// Internal to umbra_scene: shared by Scene.cpp and SceneParse.cpp.
#include "scene/Scene.hpp"

#include <string>

namespace umbra::scene::detail {

/// Throws SceneError("<file>: <field>: <message>"), or "<file>: <message>" for no field.
[[noreturn]] void fail(const std::string& file, const std::string& field,
                       const std::string& message);

/// Computes the positions that depend on time (ephemeris bodies, the observer, a body
/// target) and the camera's up vector. Needs scene.hasTime when any of them does.
void resolve(Scene& scene);

} // namespace umbra::scene::detail
