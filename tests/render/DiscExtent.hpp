#pragma once
// The Sun's disc in an image, to measure its flattening by refraction: the bounding box
// of the pixels whose value exceeds a fraction of the brightest one (shared by the render
// pass's test, on HDR red, and the GUI's, on a screenshot).
#include <algorithm>

namespace umbra::test {

struct DiscExtent {
  int top = -1, bottom = -1, left = -1, right = -1;  // rows from the top, columns
  int height() const { return bottom - top + 1; }
  int width() const { return right - left + 1; }
};

/// `value(i, j)`: column i, row j (from the top) of a w x h image.
template <class Value>
DiscExtent discOf(int w, int h, const Value& value, double fraction) {
  double peak = 0.0;
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) peak = std::max(peak, double(value(i, j)));
  DiscExtent d;
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      if (value(i, j) < fraction * peak) continue;
      if (d.top < 0) d.top = j;
      d.bottom = j;
      d.left = d.left < 0 ? i : std::min(d.left, i);
      d.right = std::max(d.right, i);
    }
  return d;
}

} // namespace umbra::test
