#include "CameraBasis.h"

#include <vtkCamera.h>
#include <vtkShaderProgram.h>

#include <glm/geometric.hpp>

#include <cmath>

namespace umbra::render {

CameraBasis cameraBasis(vtkCamera* camera, int width, int height) {
  glm::dvec3 position, focal, viewUp;
  camera->GetPosition(&position.x);
  camera->GetFocalPoint(&focal.x);
  camera->GetViewUp(&viewUp.x);
  CameraBasis b;
  b.forward = glm::normalize(focal - position);
  b.right = glm::normalize(glm::cross(b.forward, viewUp));
  b.up = glm::cross(b.right, b.forward);
  b.parallel = camera->GetParallelProjection() != 0;
  b.halfHeight = b.parallel ? camera->GetParallelScale()
                            : std::tan(0.5 * camera->GetViewAngle() * 3.14159265358979323846 / 180.0);
  b.halfWidth = b.halfHeight * double(width) / height;
  return b;
}

void setVec3(vtkShaderProgram* program, const char* name, const glm::dvec3& v) {
  const float f[3] = {static_cast<float>(v.x), static_cast<float>(v.y), static_cast<float>(v.z)};
  program->SetUniform3f(name, f);
}

}  // namespace umbra::render
