// Frame timing shared by the render benches.
#pragma once

#include "BodyView.h"
#include "SceneInputs.h"
#include "scene/Scene.hpp"
#include "vtkAtmosphereTablesSource.h"
#include "vtkUmbraRenderPass.h"
#include "EglRenderWindow.h"
#include <CLI/CLI.hpp>
#include <vtkNew.h>
#include <vtkRenderWindow.h>
#include <vtk_glew.h>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace umbra::bench {

/// An example scene: in the source tree the bench was built from, else (a copy of the
/// tree on another machine) under examples/scenes/ of the working directory.
inline std::string exampleScene(const std::string& file) {
  const std::string built = std::string(UMBRA_SOURCE_DIR) + "/examples/scenes/" + file;
  return std::filesystem::exists(built) ? built : "examples/scenes/" + file;
}

/// --egl: the bench's windows on EGL pbuffers instead of X (a GPU machine with no X server).
inline void addEglOption(CLI::App& app, bool& egl) {
  app.add_flag("--egl", egl,
               "Render on EGL pbuffers, no X server needed (the first EGL device that is not Mesa's software "
               "one; UMBRA_EGL_DEVICE=N picks another)");
}
/// Switches to EGL windows when asked, or when there is no X display (as umbra render
/// does); false (the reason on stderr) when that cannot be done.
inline bool startWindows(bool egl) {
  if (!egl) {
    try {
      if (render::useEglWithoutDisplay()) std::fprintf(stderr, "no X display: rendering through EGL\n");
      return true;
    } catch (const std::exception& e) {
      std::fprintf(stderr, "%s\n", e.what());
      return false;
    }
  }
  std::string error;
  if (render::useEglRenderWindows(error)) return true;
  std::fprintf(stderr, "--egl: %s\n", error.c_str());
  return false;
}
/// The options every frame bench takes: --frames, --width, --height and --egl.
struct FrameBenchOptions {
  int frames = 20, width = 1920, height = 1080;
  bool egl = false;
};
inline void addFrameBenchOptions(CLI::App& app, FrameBenchOptions& o) {
  app.add_option("--frames", o.frames, "Frames per configuration")->capture_default_str();
  app.add_option("--width", o.width)->capture_default_str();
  app.add_option("--height", o.height)->capture_default_str();
  addEglOption(app, o.egl);
}
/// ... and a scene bench's --scene (40 frames by default).
struct SceneBenchOptions : FrameBenchOptions {
  SceneBenchOptions() { frames = 40; }
  std::string scenePath;
};
inline void addSceneBenchOptions(CLI::App& app, SceneBenchOptions& o) {
  addFrameBenchOptions(app, o);
  app.add_option("--scene", o.scenePath)->capture_default_str();
}

/// Prints which GL implementation rendered (GPU or llvmpipe), after a first frame.
inline void printRenderer(render::BodyView& view) {
  std::printf("GL: %s\n", render::glRendererString(view.GetRenderWindow()).c_str());
}

/// Per view, the median time per frame [ms]: on the GL timer (GL_TIME_ELAPSED around the
/// frame), on the wall clock (render + glFinish), and the process's CPU time over the same
/// span (all threads: with Mesa's llvmpipe the fragment work itself, and the steadier
/// figure on a machine shared with other jobs); and the GPU time of the render pass's
/// receivers, stars and atmosphere stages (GL_TIMESTAMP between the stages: what the paper's
/// Tables 1 and 2 time).
struct FrameTimes {
  std::vector<double> glMs, wallMs, cpuMs, receiversMs, starsMs, atmosphereMs;
};

/// A view of a scene's inputs as `umbra render` draws it (tables through the cache, the
/// night sky, the camera, the exposure), rendered once to warm up (shaders, textures). It
/// leaves out what `umbra render` adds for eclipses and terrain: the airless LuT is the one
/// given (not ranged to the receivers), and there is no atmospheric shadow LuT, limb-luminance
/// LuT nor terrain patch. The benches that use it compare views of one scene with a stage
/// and without it (clouds, stars, the Milky Way), which these omissions leave alike; the
/// eclipse scene among them (lunar-eclipse-2015-09-28-clouds) draws the Moon in the airless
/// shadow, not the atmosphere's.
inline std::unique_ptr<render::BodyView> sceneView(const scene::Scene& s, const pipeline::SceneInputs& in, int width,
                                                   int height, vtkImageData* lut) {
  auto v = std::make_unique<render::BodyView>(width, height, true);
  v->SetBodies(in.sun, in.bodies, lut);
  vtkNew<vtkAtmosphereTablesSource> source;
  pipeline::applySceneAtmosphere(*v, in, source);
  pipeline::showSceneSky(*v, in);
  v->SetCamera(in.camera);
  v->SetExposureEV(s.exposureEv);
  v->Render();
  return v;
}

inline double processCpuMs() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return t.tv_sec * 1e3 + t.tv_nsec * 1e-6;
}

inline double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

// Renders each view `frames` times, interleaved frame by frame so that a change in the
// machine's load hits every view alike, and returns the medians. The views are expected
// to be warmed up already (shaders compiled, textures uploaded).
inline FrameTimes medianFrameTimes(const std::vector<render::BodyView*>& views, int frames) {
  const std::size_t n = views.size();
  std::vector<std::vector<double>> gl(n), wall(n), cpu(n), receivers(n), stars(n), atmosphere(n);
  std::vector<GLuint> queries(n, 0);
  for (std::size_t k = 0; k < n; ++k) {
    views[k]->GetRenderWindow()->MakeCurrent();
    glGenQueries(1, &queries[k]);
    views[k]->GetRenderPass()->SetStageTiming(true);
  }
  for (int f = 0; f < frames; ++f) {
    for (std::size_t k = 0; k < n; ++k) {
      vtkRenderWindow* w = views[k]->GetRenderWindow();
      w->MakeCurrent();
      const auto t0 = std::chrono::steady_clock::now();
      const double c0 = processCpuMs();
      glBeginQuery(GL_TIME_ELAPSED, queries[k]);
      views[k]->Render();
      w->MakeCurrent();
      glEndQuery(GL_TIME_ELAPSED);
      glFinish();
      cpu[k].push_back(processCpuMs() - c0);
      wall[k].push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
      GLuint64 ns = 0;
      glGetQueryObjectui64v(queries[k], GL_QUERY_RESULT, &ns);
      gl[k].push_back(ns * 1e-6);
      vtkUmbraRenderPass::StageTimes stages;
      if (views[k]->GetRenderPass()->GetLastStageTimes(stages)) {
        receivers[k].push_back(stages.receiversMs);
        stars[k].push_back(stages.starsMs);
        atmosphere[k].push_back(stages.atmosphereMs);
      }
    }
  }
  FrameTimes t;
  for (std::size_t k = 0; k < n; ++k) {
    views[k]->GetRenderWindow()->MakeCurrent();
    glDeleteQueries(1, &queries[k]);
    views[k]->GetRenderPass()->SetStageTiming(false);
    t.receiversMs.push_back(receivers[k].empty() ? 0.0 : median(receivers[k]));
    t.starsMs.push_back(stars[k].empty() ? 0.0 : median(stars[k]));
    t.atmosphereMs.push_back(atmosphere[k].empty() ? 0.0 : median(atmosphere[k]));
    t.glMs.push_back(median(gl[k]));
    t.wallMs.push_back(median(wall[k]));
    t.cpuMs.push_back(median(cpu[k]));
  }
  return t;
}

// The same for views a bench owns.
inline FrameTimes medianFrameTimes(const std::vector<std::unique_ptr<render::BodyView>>& views, int frames) {
  std::vector<render::BodyView*> timed;
  for (const auto& v : views) timed.push_back(v.get());
  return medianFrameTimes(timed, frames);
}

// The wall-clock medians alone.
inline std::vector<double> medianFrameWallMs(const std::vector<render::BodyView*>& views, int frames) {
  return medianFrameTimes(views, frames).wallMs;
}

}  // namespace umbra::bench
