// BodyView: HDR and PNG output, exposure, depth ordering across scales, the LuT texture's
// format, and clear errors for bad input.
#include "RenderTestSupport.hpp"
#include "vtkUmbraRenderPass.h"

#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkOpenGLTexture.h>
#include <vtkPNGReader.h>
#include <vtkPointData.h>
#include <vtkRenderWindow.h>
#include <vtkTextureObject.h>
#include <vtkUnsignedCharArray.h>
#include <vtk_glew.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <unistd.h>
#include <filesystem>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

using namespace umbra;
using namespace umbra::render;
using namespace umbra::render::test;

namespace {

SunLight sunAtMinusOneAu() {
  SunLight sun;
  sun.positionM = {-kAu, 0.0, 0.0};
  return sun;
}

struct ScreenScene {
  SunLight sun = sunAtMinusOneAu();
  SphereBody earth{"Earth", {0.0, 0.0, 0.0}, kEarthRadius, {0.3, 0.3, 0.3}};
  SphereBody screen{"Screen", {kMoonDistance + 2.0e7, 0.0, 0.0}, 2.0e7, {0.5, 0.4, 0.3}};
  ViewCamera camera;
  ScreenScene() {
    camera.positionM = {kMoonDistance - 5.0e7, 0.0, 0.0};
    camera.targetM = screen.centreM;
    camera.up = {0.0, 0.0, 1.0};
    camera.parallel = true;
    camera.parallelScaleM = 1.2e7;
  }
  void setUp(BodyView& view) const {
    view.SetBodies(sun, {earth, screen}, testLutImage());
    view.SetCamera(camera);
  }
};

std::filesystem::path tempDir() {
  // A new, empty directory (mkdtemp): one named by the process id alone can hold the files
  // of an earlier test process that had the same id.
  std::string pattern = (std::filesystem::temp_directory_path() / "umbra-body-view-XXXXXX").string();
  if (!::mkdtemp(pattern.data())) throw std::runtime_error("mkdtemp failed for " + pattern);
  return pattern;
}

std::vector<unsigned char> readPng(const std::string& path, int& w, int& h) {
  vtkNew<vtkPNGReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  int dims[3];
  reader->GetOutput()->GetDimensions(dims);
  w = dims[0];
  h = dims[1];
  auto* px = vtkUnsignedCharArray::SafeDownCast(reader->GetOutput()->GetPointData()->GetScalars());
  if (!px) return {};
  return std::vector<unsigned char>(px->GetPointer(0), px->GetPointer(0) + px->GetNumberOfValues());
}

double srgbDecode(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }

} // namespace

TEST(BodyView, HdrIsFiniteAndPngIsNeitherBlackNorWhite) {
  BodyView view(256, 256, true);
  useSharedDisplay(view.GetRenderWindow());
  ScreenScene scene;
  scene.setUp(view);
  view.SetExposureEV(-8.0);
  view.Render();
  std::vector<float> hdr;
  int w = 0, h = 0;
  ASSERT_NO_THROW(view.ReadHdr(hdr, w, h));  // throws on non-finite values
  ASSERT_EQ(hdr.size(), static_cast<std::size_t>(w) * h * 3);
  float maxValue = 0.0f;
  for (float v : hdr) {
    ASSERT_TRUE(std::isfinite(v));
    ASSERT_GE(v, 0.0f);
    maxValue = std::max(maxValue, v);
  }
  // Unshadowed: 0.5 / pi * 1361 W/m^2 ~ 217 W m^-2 sr^-1 (red channel).
  EXPECT_GT(maxValue, 150.0f);
  EXPECT_LT(maxValue, 220.0f);
  EXPECT_EQ(hdr[3 * (w * h / 2 + w / 2)], 0.0f) << "the centre is in the umbra";

  const auto dir = tempDir();
  const std::string path = (dir / "screen.png").string();
  view.WritePng(path);
  int pw = 0, ph = 0;
  const std::vector<unsigned char> png = readPng(path, pw, ph);
  EXPECT_EQ(pw, 256);
  EXPECT_EQ(ph, 256);
  ASSERT_FALSE(png.empty());
  const auto [lo, hi] = std::minmax_element(png.begin(), png.end());
  EXPECT_EQ(*lo, 0) << "umbra and background are black";
  EXPECT_GT(*hi, 100) << "not all black";
  EXPECT_LT(*hi, 255) << "not all white";
  std::set<unsigned char> levels(png.begin(), png.end());
  EXPECT_GT(levels.size(), 50u) << "a penumbra gradient";
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    EXPECT_EQ(entry.path().filename().string(), "screen.png") << "no temporary file left";
  }
  std::filesystem::remove_all(dir);
}

TEST(BodyView, PlusOneEvDoublesThePreToneMapValue) {
  BodyView view(128, 128, true);
  useSharedDisplay(view.GetRenderWindow());
  ScreenScene scene;
  scene.setUp(view);
  view.SetToneMapping(vtkUmbraRenderPass::Linear);
  const double ev = std::log2(0.2 / 217.0);  // unshadowed red ~ 0.2 after exposure
  const auto dir = tempDir();
  std::vector<std::vector<unsigned char>> shots;
  std::vector<std::vector<float>> hdrs;
  for (double e : {ev, ev + 1.0}) {
    view.SetExposureEV(e);
    view.Render();
    const std::string path = (dir / "ev.png").string();
    view.WritePng(path);
    int w = 0, h = 0;
    shots.push_back(readPng(path, w, h));
    std::vector<float> hdr;
    view.ReadHdr(hdr, w, h);
    hdrs.push_back(hdr);
  }
  std::filesystem::remove_all(dir);
  EXPECT_EQ(hdrs[0], hdrs[1]) << "exposure only changes the display";
  int compared = 0;
  for (std::size_t k = 0; k < shots[0].size(); ++k) {
    const double a = srgbDecode(shots[0][k] / 255.0), b = srgbDecode(shots[1][k] / 255.0);
    if (a < 0.05 || a > 0.45) continue;
    EXPECT_NEAR(b / a, 2.0, 0.06) << "value " << k;
    ++compared;
  }
  EXPECT_GT(compared, 1000);
}

// Camera 1 m above a large body, looking at a nearer and a farther body 1e8 and 2e8 m
// away that overlap on screen: near/far span 1e9, the logarithmic depth keeps the order
// (standard depth would give both far bodies the same depth value).
TEST(BodyView, DepthOrderHoldsFromOneMetreToAuScale) {
  SunLight sun;
  sun.positionM = glm::dvec3(-0.5, -0.5, 0.7071) * kAu;
  const double groundR = 1.0e6;
  const SphereBody ground{"Ground", {0.0, 0.0, 0.0}, groundR, {0.0, 1.0, 0.0}};
  const SphereBody nearBody{"Near", {1.0e8, 0.0, groundR}, 1.0e6, {1.0, 0.0, 0.0}};
  const SphereBody farBody{"Far", {2.0e8, 0.0, groundR}, 1.0e7, {0.0, 0.0, 1.0}};
  ViewCamera cam;
  cam.positionM = {0.0, 0.0, groundR + 1.0};
  cam.targetM = {1.0e8, 0.0, groundR + 1.0};
  cam.up = {0.0, 0.0, 1.0};
  cam.fovDeg = 10.0;
  BodyView view(256, 256, true);
  useSharedDisplay(view.GetRenderWindow());
  view.SetBodies(sun, {ground, nearBody, farBody}, testLutImage());
  view.SetCamera(cam);
  double nearM = 0, farM = 0;
  view.GetClippingRange(nearM, farM);
  EXPECT_LT(nearM, 1.0);
  EXPECT_GT(farM, 2.1e8);
  view.Render();
  std::vector<float> hdr;
  int w = 0, h = 0;
  view.ReadHdr(hdr, w, h);
  auto px = [&](int i, int j) { return &hdr[3 * (static_cast<std::size_t>(j) * w + i)]; };
  // 0.3 degrees above the centre: the near body, in front of the far one.
  const float* a = px(128, 120);
  EXPECT_GT(a[0], 0.0f);
  EXPECT_EQ(a[2], 0.0f);
  // 1.5 degrees above the centre: only the far body.
  const float* b = px(128, 90);
  EXPECT_EQ(b[0], 0.0f);
  EXPECT_GT(b[2], 0.0f);
  // The bottom row: the ground right below the camera, in front of everything.
  const float* c = px(128, 250);
  EXPECT_GT(c[1], 0.0f);
  EXPECT_EQ(c[0], 0.0f);
  EXPECT_EQ(c[2], 0.0f);
}

TEST(BodyView, ShadowLutIsBoundAsLinearClampedFloatTexture) {
  BodyView view(64, 64, true);
  useSharedDisplay(view.GetRenderWindow());
  ScreenScene scene;
  scene.setUp(view);
  view.Render();
  auto* tex = vtkOpenGLTexture::SafeDownCast(view.GetShading().GetShadowLutTexture());
  ASSERT_NE(tex, nullptr);
  vtkTextureObject* to = tex->GetTextureObject();
  ASSERT_NE(to, nullptr);
  view.GetRenderWindow()->MakeCurrent();
  to->Bind();
  GLint format = 0, minFilter = 0, magFilter = 0, wrapS = 0, wrapT = 0, w = 0, h = 0;
  glGetTexLevelParameteriv(GL_TEXTURE_2D, 0, GL_TEXTURE_INTERNAL_FORMAT, &format);
  glGetTexLevelParameteriv(GL_TEXTURE_2D, 0, GL_TEXTURE_WIDTH, &w);
  glGetTexLevelParameteriv(GL_TEXTURE_2D, 0, GL_TEXTURE_HEIGHT, &h);
  glGetTexParameteriv(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, &minFilter);
  glGetTexParameteriv(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, &magFilter);
  glGetTexParameteriv(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, &wrapS);
  glGetTexParameteriv(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, &wrapT);
  std::vector<float> texels(static_cast<std::size_t>(64) * 64 * 3);
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glGetTexImage(GL_TEXTURE_2D, 0, GL_RGB, GL_FLOAT, texels.data());
  to->Deactivate();
  EXPECT_EQ(format, GL_RGBA32F);  // RGB padded with alpha: llvmpipe samples it faster than RGB32F
  EXPECT_EQ(w, 64);
  EXPECT_EQ(h, 64);
  EXPECT_EQ(minFilter, GL_LINEAR) << "no mipmaps";
  EXPECT_EQ(magFilter, GL_LINEAR);
  EXPECT_EQ(wrapS, GL_CLAMP_TO_EDGE);
  EXPECT_EQ(wrapT, GL_CLAMP_TO_EDGE);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  // The values arrive unmodified (bit for bit), texel (i, j) at row j.
  EXPECT_EQ(texels, testLut().rgb);
}

// The receiver's shader holds its occluder count as a constant (EclipseShading): changing
// the occluders after the receivers are made must rebuild it. A screen drawn alone, then
// given Earth as an occluder, gets the umbra of a view that always had Earth, bit for bit;
// without occluders again, its own first value.
TEST(BodyView, ChangingTheOccludersRebuildsTheReceiverShader) {
  ScreenScene scene;
  auto centreOf = [](BodyView& v) {
    v.Render();
    std::vector<float> hdr;
    int w = 0, h = 0;
    v.ReadHdr(hdr, w, h);
    const std::size_t c = 3 * (static_cast<std::size_t>(w) * h / 2 + w / 2);
    return std::vector<float>(hdr.begin() + c, hdr.begin() + c + 3);
  };
  BodyView view(64, 64, true), always(64, 64, true);
  for (BodyView* v : {&view, &always}) useSharedDisplay(v->GetRenderWindow());
  scene.setUp(always);
  view.SetBodies(scene.sun, {scene.screen}, testLutImage());
  view.SetCamera(scene.camera);
  const std::vector<float> lit = centreOf(view);
  EXPECT_GT(lit[0], 150.0f);
  view.GetShading().SetOccluders({scene.earth, scene.screen});
  const std::vector<float> shadowed = centreOf(view);
  EXPECT_EQ(shadowed[0], 0.0f) << "the centre is in the umbra";
  EXPECT_EQ(shadowed, centreOf(always));
  view.GetShading().SetOccluders({});
  EXPECT_EQ(centreOf(view), lit);
}

TEST(BodyView, BadInputThrowsClearly) {
  EXPECT_THROW(BodyView(0, 10, true), std::invalid_argument);
  BodyView view(32, 32, true);
  useSharedDisplay(view.GetRenderWindow());
  ScreenScene scene;
  EXPECT_THROW(view.Render(), std::runtime_error);  // no camera yet
  std::vector<float> hdr;
  int w = 0, h = 0;
  EXPECT_THROW(view.ReadHdr(hdr, w, h), std::runtime_error);  // nothing rendered
  EXPECT_THROW(view.SetBodies(scene.sun, {scene.earth}, nullptr), std::invalid_argument);

  vtkNew<vtkImageData> bytes;  // not float
  bytes->SetDimensions(4, 4, 1);
  bytes->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  EXPECT_THROW(view.SetBodies(scene.sun, {scene.earth}, bytes), std::invalid_argument);
  vtkNew<vtkImageData> gray;  // one component
  gray->SetDimensions(4, 4, 1);
  gray->AllocateScalars(VTK_FLOAT, 1);
  EXPECT_THROW(view.SetBodies(scene.sun, {scene.earth}, gray), std::invalid_argument);

  auto lut = testLutImage();
  SphereBody bad = scene.earth;
  bad.radiusM = std::nan("");
  EXPECT_THROW(view.SetBodies(scene.sun, {bad}, lut), std::invalid_argument);
  EXPECT_THROW(view.SetBodies(scene.sun, {scene.earth, scene.earth}, lut), std::invalid_argument);
  std::vector<SphereBody> six;
  for (int i = 0; i < 6; ++i) six.push_back({"b" + std::to_string(i), {1e9 * i, 0, 0}, 1e6, {0.1, 0.1, 0.1}});
  EXPECT_THROW(view.SetBodies(scene.sun, six, lut), std::invalid_argument);

  scene.setUp(view);
  ViewCamera inside = scene.camera;
  inside.parallel = false;
  inside.positionM = {1000.0, 0.0, 0.0};  // inside Earth
  try {
    view.SetCamera(inside);
    FAIL() << "camera inside a body accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("Earth"), std::string::npos) << e.what();
  }
  ViewCamera degenerate = scene.camera;
  degenerate.up = {1.0, 0.0, 0.0};  // parallel to the view direction
  EXPECT_THROW(view.SetCamera(degenerate), std::invalid_argument);
  EXPECT_THROW(view.SetExposureEV(std::nan("")), std::invalid_argument);

  view.Render();
  const std::string missing = "/nonexistent-umbra-dir/out.png";
  try {
    view.WritePng(missing);
    FAIL() << "writing into a missing directory succeeded";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(missing), std::string::npos) << e.what();
  }
}
