#pragma once
// A view ray in its plane for the precomputation's integrals: straight, or traced through
// the refractive medium (Refraction.hpp), with its position and tangent at any arc length.
#include "Refraction.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace umbra::atmosphere::stages {


struct Knot {
  double s, x, y, tx, ty;
};

/// A ray in its plane (start at (0, r), first heading towards +x): straight (two knots) or
/// traced (a knot per RK4 step), cubic Hermite in position between the knots.
struct Path {
  std::vector<Knot> knots;
  double length = 0.0;

  /// Position at arc length s (eval's, without the tangent); `seg` as eval's.
  void position(double s, std::size_t& seg, double& x, double& y) const {
    if (knots.size() < 2) {
      x = knots.front().x, y = knots.front().y;
      return;
    }
    while (seg + 2 < knots.size() && s > knots[seg + 1].s) ++seg;
    while (seg > 0 && s < knots[seg].s) --seg;
    const Knot& a = knots[seg];
    const Knot& c = knots[seg + 1];
    const double L = c.s - a.s;
    const double u = L > 0.0 ? std::clamp((s - a.s) / L, 0.0, 1.0) : 0.0;
    const double u2 = u * u, u3 = u2 * u;
    const double h00 = 2 * u3 - 3 * u2 + 1, h10 = u3 - 2 * u2 + u, h01 = -2 * u3 + 3 * u2, h11 = u3 - u2;
    x = h00 * a.x + h10 * L * a.tx + h01 * c.x + h11 * L * c.tx;
    y = h00 * a.y + h10 * L * a.ty + h01 * c.y + h11 * L * c.ty;
  }
  /// Position and unit tangent at arc length s; `seg` is a cursor for increasing s.
  void eval(double s, std::size_t& seg, double& x, double& y, double& tx, double& ty) const {
    if (knots.size() < 2) {
      const Knot& k = knots.front();
      x = k.x, y = k.y, tx = k.tx, ty = k.ty;
      return;
    }
    position(s, seg, x, y);  // moves seg to the knot segment holding s
    const Knot& a = knots[seg];
    const Knot& c = knots[seg + 1];
    const double L = c.s - a.s;
    const double u = L > 0.0 ? std::clamp((s - a.s) / L, 0.0, 1.0) : 0.0;
    const double u2 = u * u;
    const double d00 = 6 * u2 - 6 * u, d10 = 3 * u2 - 4 * u + 1, d01 = -d00, d11 = 3 * u2 - 2 * u;
    double dx = d00 * a.x / std::max(L, 1e-300) + d10 * a.tx + d01 * c.x / std::max(L, 1e-300) + d11 * c.tx;
    double dy = d00 * a.y / std::max(L, 1e-300) + d10 * a.ty + d01 * c.y / std::max(L, 1e-300) + d11 * c.ty;
    if (!(L > 0.0)) dx = a.tx, dy = a.ty;
    const double n = std::sqrt(dx * dx + dy * dy);
    if (n > 0.0) tx = dx / n, ty = dy / n; else tx = a.tx, ty = a.ty;
  }
};

inline Path straightPath(double r, double mu, double length) {
  const double sz = std::sqrt(std::max(0.0, (1.0 - mu) * (1.0 + mu)));
  Path p;
  p.length = length;
  p.knots.push_back({0.0, 0.0, r, sz, mu});
  p.knots.push_back({length, sz * length, r + mu * length, sz, mu});
  return p;
}

/// The ray traced by traceRay; stopAtGround: up to the first contact with the ground,
/// else all of it (through the ground, as Refraction.hpp continues it).
inline Path tracedPath(const RefractiveMedium& medium, double r, double mu, double stepM, bool stopAtGround) {
  Path p;
  TraceOptions o;
  o.stepM = stepM;
  bool stopped = false;
  o.point = [&](const RayPoint& q) {
    if (stopped) return;
    if (q.underGround && stopAtGround) {
      stopped = true;
      return;
    }
    if (!p.knots.empty() && q.pathLengthM <= p.knots.back().s + 1e-9) {
      if (p.knots.size() > 1) p.knots.back() = {q.pathLengthM, q.xM, q.yM, q.dirX, q.dirY};
      return;
    }
    p.knots.push_back({q.pathLengthM, q.xM, q.yM, q.dirX, q.dirY});
  };
  traceRay(medium, r, mu, o);
  if (p.knots.empty()) {
    const double sz = std::sqrt(std::max(0.0, (1.0 - mu) * (1.0 + mu)));
    p.knots.push_back({0.0, 0.0, r, sz, mu});
  }
  p.length = p.knots.back().s - p.knots.front().s;
  // traceRay starts at 0 from inside the shell; shift in case it entered from above.
  const double s0 = p.knots.front().s;
  for (Knot& k : p.knots) k.s -= s0;
  return p;
}

}  // namespace umbra::atmosphere::stages
