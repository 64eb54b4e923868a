#pragma once
// The terrain soft shadow computed on the GPU: terrain/glsl/TerrainShadow.glsl run over a
// full-screen quad, one fragment per DEM sample, into a float framebuffer (the GLSL twin
// of terrain::visibleFractionMap with the DP method, for the render pass and for the
// CPU-GLSL agreement test). Needs an OpenGL render window (X display).
#include "MaximumMipmap.hpp"
#include "SoftShadow.hpp"

#include <vector>

class vtkRenderWindow;

namespace umbra::render {

struct GpuTerrainShadow {
  std::vector<float> fraction;  ///< per DEM sample, row-major like the heights
  std::vector<float> horizonRad;
};

/// Throws std::runtime_error if the window has no OpenGL context or the shader fails.
GpuTerrainShadow terrainShadowGpu(vtkRenderWindow* window, const terrain::HeightField& field,
                                  const terrain::MaximumMipmap& mip, const terrain::SunDisc& sun, int levels);

} // namespace umbra::render
