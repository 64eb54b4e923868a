// Frame timing shared by the render benches.
#pragma once

#include "BodyView.h"
#include <vtkRenderWindow.h>
#include <algorithm>
#include <chrono>
#include <vector>

namespace umbra::bench {

// Renders each view `frames` times, interleaved, and returns each view's median wall time per frame [ms]
// (render + WaitForCompletion). The views are expected to be warmed up already.
inline std::vector<double> medianFrameWallMs(const std::vector<render::BodyView*>& views, int frames) {
  std::vector<std::vector<double>> times(views.size());
  for (int f = 0; f < frames; ++f) {
    for (std::size_t k = 0; k < views.size(); ++k) {
      const auto t0 = std::chrono::steady_clock::now();
      views[k]->Render();
      views[k]->GetRenderWindow()->WaitForCompletion();
      times[k].push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    }
  }
  std::vector<double> median(views.size());
  for (std::size_t k = 0; k < views.size(); ++k) {
    std::sort(times[k].begin(), times[k].end());
    median[k] = times[k][times[k].size() / 2];
  }
  return median;
}

}  // namespace umbra::bench
