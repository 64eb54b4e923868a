#pragma once
// The renderer camera's basis in double, as the render pass's own programs take it
// (AtmosphereComposite.glsl, StarSplat.glsl): forward F and the unit right and up vectors,
// with the frame's half extents (perspective: at unit distance; parallel: in metres). The
// view ray through NDC (x, y) of a perspective view is F + x X + y Y, X = right halfWidth,
// Y = up halfHeight; a parallel view's rays start at x X + y Y and go along F.
#include <glm/vec3.hpp>

class vtkCamera;
class vtkShaderProgram;

namespace umbra::render {

struct CameraBasis {
  glm::dvec3 forward{0.0, 0.0, -1.0}, right{1.0, 0.0, 0.0}, up{0.0, 1.0, 0.0};
  double halfWidth = 1.0, halfHeight = 1.0;
  bool parallel = false;
  glm::dvec3 rayX() const { return right * halfWidth; }
  glm::dvec3 rayY() const { return up * halfHeight; }
};

/// The basis of `camera` for a frame of width x height pixels.
CameraBasis cameraBasis(vtkCamera* camera, int width, int height);

/// Sets the vec3 uniform `name` of `program` from double values.
void setVec3(vtkShaderProgram* program, const char* name, const glm::dvec3& v);

}  // namespace umbra::render
