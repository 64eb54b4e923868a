#include "TerrainShadowGpu.h"

#include "TerrainShadowGlsl.hpp"

#include <vtkNew.h>
#include <vtkOpenGLFramebufferObject.h>
#include <vtkOpenGLQuadHelper.h>
#include <vtkOpenGLRenderUtilities.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkOpenGLShaderCache.h>
#include <vtkOpenGLState.h>
#include <vtkShaderProgram.h>
#include <vtkTextureObject.h>
#include <vtk_glew.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace umbra::render {
namespace {

constexpr float kNoData = -1e30f;

vtkSmartPointer<vtkTextureObject> floatTexture(vtkOpenGLRenderWindow* w, int width, int height, const float* data) {
  auto t = vtkSmartPointer<vtkTextureObject>::New();
  t->SetContext(w);
  t->SetMinificationFilter(vtkTextureObject::Nearest);
  t->SetMagnificationFilter(vtkTextureObject::Nearest);
  t->SetWrapS(vtkTextureObject::ClampToEdge);
  t->SetWrapT(vtkTextureObject::ClampToEdge);
  t->SetInternalFormat(GL_R32F);
  t->SetFormat(GL_RED);
  t->SetDataType(GL_FLOAT);
  if (!t->Create2DFromRaw(width, height, 1, VTK_FLOAT, const_cast<float*>(data)))
    throw std::runtime_error("terrain shadow (GPU): cannot create a " + std::to_string(width) + "x" +
                             std::to_string(height) + " float texture");
  return t;
}

} // namespace

TerrainShadowTextures terrainShadowTextures(const terrain::HeightField& f, const terrain::MaximumMipmap& mip) {
  if (mip.levels() > 16) throw std::runtime_error("terrain shadow (GPU): more than 16 mipmap levels");
  TerrainShadowTextures t;
  t.heights.resize(f.heightsM.size());
  for (std::size_t k = 0; k < t.heights.size(); ++k)
    t.heights[k] = std::isnan(f.heightsM[k]) ? kNoData : static_cast<float>(f.heightsM[k]);
  t.levels = mip.levels();
  t.atlasWidth = mip.width(0);
  for (int m = 0; m < mip.levels(); ++m) {
    t.row[m] = t.atlasHeight;
    t.width[m] = mip.width(m), t.height[m] = mip.height(m);
    t.atlasHeight += mip.height(m);
  }
  t.atlas.assign(static_cast<std::size_t>(t.atlasWidth) * t.atlasHeight, kNoData);
  for (int m = 0; m < mip.levels(); ++m)
    for (int j = 0; j < mip.height(m); ++j)
      for (int i = 0; i < mip.width(m); ++i) {
        const double v = mip.max(m, i, j);
        t.atlas[static_cast<std::size_t>(t.row[m] + j) * t.atlasWidth + i] = std::isinf(v) ? kNoData : static_cast<float>(v);
      }
  return t;
}

void setTerrainShadowUniforms(vtkShaderProgram& program, const TerrainShadowTextures& t, const terrain::HeightField& f,
                              const terrain::MaximumMipmap& mip, const terrain::SunDisc& sun, int levels,
                              double searchToTexels) {
  program.SetUniform1iv("umbraMipRow", 16, t.row);
  program.SetUniform1iv("umbraMipWidth", 16, t.width);
  program.SetUniform1iv("umbraMipHeight", 16, t.height);
  program.SetUniformi("umbraMipLevels", t.levels);
  const int grid[2] = {f.width, f.height};
  program.SetUniform2i("umbraGridSize", grid);
  program.SetUniformf("umbraSpacingM", static_cast<float>(f.spacingM));
  program.SetUniformf("umbraRadiusM", static_cast<float>(f.bodyRadiusM));
  program.SetUniformf("umbraGlobalMaxM", static_cast<float>(mip.globalMax()));
  const glm::dvec3 L = glm::normalize(sun.direction);
  const float direction[3] = {float(L.x), float(L.y), float(L.z)};
  program.SetUniform3f("umbraSunDirection", direction);
  program.SetUniformf("umbraSunRadius", static_cast<float>(sun.angularRadiusRad));
  program.SetUniformf("umbraLimbDarkening", static_cast<float>(sun.limbDarkening));
  program.SetUniformi("umbraLevels", levels);
  program.SetUniformf("umbraSearchToTexels", static_cast<float>(std::min(searchToTexels, 1e30)));
}


GpuTerrainShadow terrainShadowGpu(vtkRenderWindow* window, const terrain::HeightField& f,
                                  const terrain::MaximumMipmap& mip, const terrain::SunDisc& sun, int levels) {
  auto* w = vtkOpenGLRenderWindow::SafeDownCast(window);
  if (!w) throw std::runtime_error("terrain shadow (GPU): needs an OpenGL render window");
  w->Initialize();
  w->MakeCurrent();

  const TerrainShadowTextures t = terrainShadowTextures(f, mip);
  auto heightTexture = floatTexture(w, f.width, f.height, t.heights.data());
  auto atlasTexture = floatTexture(w, t.atlasWidth, t.atlasHeight, t.atlas.data());

  auto colour = vtkSmartPointer<vtkTextureObject>::New();
  colour->SetContext(w);
  colour->SetMinificationFilter(vtkTextureObject::Nearest);
  colour->SetMagnificationFilter(vtkTextureObject::Nearest);
  colour->SetInternalFormat(GL_RGBA32F);
  colour->SetFormat(GL_RGBA);
  colour->SetDataType(GL_FLOAT);
  if (!colour->Allocate2D(f.width, f.height, 4, VTK_FLOAT))
    throw std::runtime_error("terrain shadow (GPU): cannot allocate the float framebuffer");
  vtkNew<vtkOpenGLFramebufferObject> fbo;
  fbo->SetContext(w);

  std::string fs = vtkOpenGLRenderUtilities::GetFullScreenQuadFragmentShaderTemplate();
  vtkShaderProgram::Substitute(fs, "//VTK::FSQ::Decl", std::string(terrain::kTerrainShadowGlsl) + "\n//VTK::FSQ::Decl");
  vtkShaderProgram::Substitute(fs, "//VTK::FSQ::Impl",
                               "  vec2 shadow = umbraTerrainShadow(ivec2(gl_FragCoord.xy));\n"
                               "  gl_FragData[0] = vec4(shadow, texCoord.x, 1.0);  // (texCoord: keeps the quad's attribute)\n"
                               "//VTK::FSQ::Impl");
  vtkOpenGLQuadHelper quad(w, vtkOpenGLRenderUtilities::GetFullScreenQuadVertexShader().c_str(), fs.c_str(), "");
  if (!quad.Program || !quad.Program->GetCompiled())
    throw std::runtime_error("terrain shadow (GPU): the shader does not compile");
  vtkShaderProgram* program = quad.Program;
  heightTexture->Activate();
  atlasTexture->Activate();
  program->SetUniformi("umbraHeights", heightTexture->GetTextureUnit());
  program->SetUniformi("umbraMipAtlas", atlasTexture->GetTextureUnit());
  setTerrainShadowUniforms(*program, t, f, mip, sun, levels);

  vtkOpenGLState* state = w->GetState();
  state->PushFramebufferBindings();
  fbo->Bind();
  fbo->AddColorAttachment(0, colour);
  fbo->ActivateDrawBuffer(0);
  if (!fbo->StartNonOrtho(f.width, f.height)) {
    state->PopFramebufferBindings();
    throw std::runtime_error("terrain shadow (GPU): the framebuffer is incomplete");
  }
  state->vtkglViewport(0, 0, f.width, f.height);
  state->vtkglScissor(0, 0, f.width, f.height);
  state->vtkglDisable(GL_SCISSOR_TEST);
  state->vtkglDisable(GL_BLEND);
  state->vtkglDisable(GL_DEPTH_TEST);
  quad.Render();
  std::vector<float> pixels(static_cast<std::size_t>(f.width) * f.height * 4);
  fbo->ActivateReadBuffer(0);
  glReadPixels(0, 0, f.width, f.height, GL_RGBA, GL_FLOAT, pixels.data());
  state->PopFramebufferBindings();
  heightTexture->Deactivate();
  atlasTexture->Deactivate();

  GpuTerrainShadow out;
  out.fraction.resize(f.heightsM.size());
  out.horizonRad.resize(f.heightsM.size());
  for (std::size_t k = 0; k < out.fraction.size(); ++k) out.fraction[k] = pixels[4 * k], out.horizonRad[k] = pixels[4 * k + 1];
  return out;
}

} // namespace umbra::render
