#pragma once
// The terrain soft shadow computed on the GPU: terrain/glsl/TerrainShadow.glsl run over a
// full-screen quad, one fragment per DEM sample, into a float framebuffer (the GLSL twin
// of terrain::visibleFractionMap with the DP method, for the render pass and for the
// CPU-GLSL agreement test). Needs an OpenGL render window (X display).
#include "MaximumMipmap.hpp"
#include "SoftShadow.hpp"

#include <vector>

class vtkRenderWindow;
class vtkShaderProgram;

namespace umbra::render {

/// What TerrainShadow.glsl reads: the heights (no data as -1e30) and the maximum mipmap
/// as one atlas, level m at rows row[m] ... (float texture data, row-major).
struct TerrainShadowTextures {
  std::vector<float> heights, atlas;
  int atlasWidth = 0, atlasHeight = 0;
  int row[16] = {0}, width[16] = {0}, height[16] = {0};
  int levels = 0;
};
/// Throws std::runtime_error for more than 16 mipmap levels.
TerrainShadowTextures terrainShadowTextures(const terrain::HeightField& field, const terrain::MaximumMipmap& mip);
/// Sets every uniform of TerrainShadow.glsl but the two samplers; the search runs along
/// the footprint up to searchToTexels (the whole of it by default).
void setTerrainShadowUniforms(vtkShaderProgram& program, const TerrainShadowTextures& textures,
                              const terrain::HeightField& field, const terrain::MaximumMipmap& mip,
                              const terrain::SunDisc& sun, int levels, double searchToTexels = 1e30);

struct GpuTerrainShadow {
  std::vector<float> fraction;  ///< per DEM sample, row-major like the heights
  std::vector<float> horizonRad;
};

/// Throws std::runtime_error if the window has no OpenGL context or the shader fails.
GpuTerrainShadow terrainShadowGpu(vtkRenderWindow* window, const terrain::HeightField& field,
                                  const terrain::MaximumMipmap& mip, const terrain::SunDisc& sun, int levels);

} // namespace umbra::render
