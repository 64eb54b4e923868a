// GLSL twin of terrain/SoftShadow.cpp (the dynamic-programming search and Eq. 6-7) and of
// eclipse::visibleFractionAboveHorizon*. Keep the two side by side: tests/render compares
// them sample by sample. Single precision: every angle is formed from differences that
// are small numbers themselves (the chord between two unit vectors, heights relative to
// the receiver), never from 1.7e6 m radii subtracted from each other.

uniform sampler2D umbraHeights;    // R32F, one texel per DEM sample; no data < -1e29
uniform sampler2D umbraMipAtlas;   // R32F, maximum mipmap level m at rows umbraMipRow[m]...
uniform int umbraMipRow[16];
uniform int umbraMipWidth[16];
uniform int umbraMipHeight[16];
uniform int umbraMipLevels;
uniform ivec2 umbraGridSize;
uniform float umbraSpacingM;
uniform float umbraRadiusM;
uniform float umbraGlobalMaxM;
uniform vec3 umbraSunDirection;    // tangent frame, unit
uniform float umbraSunRadius;      // rad
uniform float umbraLimbDarkening;
uniform int umbraLevels;           // N'
uniform float umbraSearchToTexels; // the footprint searched ends here at the latest (ShadowOptions::toTexels)

const float umbraNoData = -1e29;
const float umbraStartTexels = 1e-3;
const float umbraToleranceRad = 2e-6;

struct UmbraProfile {
  vec3 a, b;         // up at the receiver, towards the Sun in its vertical plane
  vec2 g0, dir;      // footprint in grid units
  vec2 pa;           // receiver on the tangent plane [m]
  float normA;       // |(pa, R)|
  float hp;          // receiver height [m]
  float e;           // the Sun's elevation
  float sEnd;
};

// The heights at the corners of cell c: (h00, h10, h01, h11).
vec4 umbraCellCorners(ivec2 c) {
  return vec4(texelFetch(umbraHeights, c, 0).r, texelFetch(umbraHeights, c + ivec2(1, 0), 0).r,
              texelFetch(umbraHeights, c + ivec2(0, 1), 0).r, texelFetch(umbraHeights, c + ivec2(1, 1), 0).r);
}

// From grid point g along d (grid units a unit of the parameter), how far in the
// parameter the next grid line lies on either axis (1e30 if d is zero).
float umbraToNextLine(vec2 g, vec2 d) {
  float next = 1e30;
  for (int a = 0; a < 2; ++a) {
    if (d[a] == 0.0) continue;
    float line = d[a] > 0.0 ? floor(g[a]) + 1.0 : ceil(g[a]) - 1.0;
    next = min(next, (line - g[a]) / d[a]);
  }
  return next;
}

// Bilinear height at footprint s relative to `base` (so that the small differences near
// the receiver keep their digits), no-data corners left out (as HeightField::bilinear);
// umbraNoData if none. The position within the cell is formed from the receiver's integer
// grid position and s, not from g0 + s dir (which would lose s's digits near the receiver).
float umbraHeightAt(vec2 g0, vec2 dir, float s, float base) {
  vec2 g = clamp(g0 + s * dir, vec2(0.0), vec2(umbraGridSize - 1));
  ivec2 c = min(ivec2(g), umbraGridSize - 2);
  vec2 f = clamp((g0 - vec2(c)) + s * dir, vec2(0.0), vec2(1.0));
  float h[4] = float[4](texelFetch(umbraHeights, c, 0).r, texelFetch(umbraHeights, c + ivec2(1, 0), 0).r,
                        texelFetch(umbraHeights, c + ivec2(0, 1), 0).r, texelFetch(umbraHeights, c + ivec2(1, 1), 0).r);
  float w[4] = float[4]((1.0 - f.x) * (1.0 - f.y), f.x * (1.0 - f.y), (1.0 - f.x) * f.y, f.x * f.y);
  float sum = 0.0, weight = 0.0, plain = 0.0;
  int valid = 0;
  for (int k = 0; k < 4; ++k) {
    if (h[k] > umbraNoData) { sum += w[k] * (h[k] - base); weight += w[k]; plain += h[k] - base; ++valid; }
  }
  if (valid == 4 || weight > 0.0) return sum / weight;
  return valid > 0 ? plain / float(valid) : umbraNoData;
}

// sin(phi) and 1 - cos(phi) of footprint point s (phi: central angle from the receiver).
vec2 umbraAngle(UmbraProfile p, float s) {
  vec2 d = s * p.dir * umbraSpacingM;
  vec2 ps = p.pa + d;
  float normS = sqrt(dot(ps, ps) + umbraRadiusM * umbraRadiusM);
  float diffSq = dot(d, ps + p.pa);   // |ps|^2 - |pa|^2
  float diffInv = -diffSq / ((normS + p.normA) * normS * p.normA);
  vec3 chord = vec3(d, 0.0) / normS + vec3(p.pa, umbraRadiusM) * diffInv;  // n_s - a
  return vec2(dot(chord, p.b), 0.5 * dot(chord, chord));
}

// Elevation above the receiver's horizontal of the point dh above the receiver over footprint s.
float umbraElevation(UmbraProfile p, vec2 angle, float dh) {
  float r = umbraRadiusM + p.hp + dh;
  return atan(dh - r * angle.y, r * angle.x);
}

float umbraTerrainElevation(UmbraProfile p, float s) {
  float dh = umbraHeightAt(p.g0, p.dir, s, p.hp);
  return dh <= umbraNoData ? -1e30 : umbraElevation(p, umbraAngle(p, s), dh);
}

// The highest elevation points up to dhMax above the receiver can reach over footprint
// [sa, sb] (SoftShadow.cpp elevationBound).
float umbraElevationBound(UmbraProfile p, float sa, float sb, float dhMax) {
  vec2 A = umbraAngle(p, sa);
  float ea = umbraElevation(p, A, dhMax);
  if (dhMax >= 0.0) return ea;
  vec2 B = umbraAngle(p, sb);
  float oneMinusCt = -dhMax / (umbraRadiusM + p.hp);
  if (A.y <= oneMinusCt && oneMinusCt <= B.y) return -2.0 * asin(sqrt(0.5 * oneMinusCt));
  return max(ea, umbraElevation(p, B, dhMax));
}

bool umbraClip(UmbraProfile p, vec2 lo, vec2 hi, inout float sa, inout float sb) {
  for (int k = 0; k < 2; ++k) {
    if (p.dir[k] == 0.0) {
      if (p.g0[k] < lo[k] || p.g0[k] > hi[k]) return false;
    } else {
      float t1 = (lo[k] - p.g0[k]) / p.dir[k], t2 = (hi[k] - p.g0[k]) / p.dir[k];
      sa = max(sa, min(t1, t2));
      sb = min(sb, max(t1, t2));
    }
  }
  return sb > sa;
}

// The vertical plane through the receiver at grid coordinates g (fractional) and height
// hp towards the Sun (SoftShadow.cpp Profile); false at its zenith / nadir.
bool umbraMakeProfileAt(vec2 g, float hp, out UmbraProfile p) {
  vec2 centre = 0.5 * vec2(umbraGridSize - 1);
  p.pa = (g - centre) * umbraSpacingM;
  p.normA = sqrt(dot(p.pa, p.pa) + umbraRadiusM * umbraRadiusM);
  p.a = vec3(p.pa, umbraRadiusM) / p.normA;
  p.hp = hp;
  vec3 L = umbraSunDirection;
  vec3 horizontal = L - dot(L, p.a) * p.a;
  float len = length(horizontal);
  p.e = atan(dot(L, p.a), len);
  p.g0 = g;
  p.b = vec3(0.0);
  p.dir = vec2(0.0);
  p.sEnd = 0.0;
  if (len < 1e-7) return false;
  p.b = horizontal / len;
  p.dir = normalize(vec2(p.b.x * p.a.z - p.a.x * p.b.z, p.b.y * p.a.z - p.a.y * p.b.z));
  float sa = 0.0, sb = 1e30;
  float gridExit = umbraClip(p, vec2(0.0), vec2(umbraGridSize - 1), sa, sb) ? sb : 0.0;
  // Volume exit: where no terrain up to the global maximum reaches the disc's lower edge.
  float lower = p.e - umbraSunRadius;
  float rp = umbraRadiusM + p.hp, rMax = umbraRadiusM + umbraGlobalMaxM;
  float volumeExit = 1e30;
  if (lower > -1.5707963) {
    if (p.hp > umbraGlobalMaxM) {
      volumeExit = lower >= -2.0 * asin(sqrt(0.5 * (p.hp - umbraGlobalMaxM) / rp)) ? 0.0 : 1e30;
    } else {
      float sg = sin(lower), cg = cos(lower);
      float lambda = -rp * sg + sqrt(max(0.0, rp * rp * sg * sg + (umbraGlobalMaxM - p.hp) * (rMax + rp)));
      vec3 x = rp * p.a + lambda * (sg * p.a + cg * p.b);
      if (x.z > 0.0) {
        vec2 g = umbraRadiusM * x.xy / x.z / umbraSpacingM + centre;
        volumeExit = max(0.0, dot(g - p.g0, p.dir));
      }
    }
  }
  p.sEnd = min(min(gridExit, volumeExit), umbraSearchToTexels);
  return true;
}

// The receiver at DEM sample ij, at its own height.
bool umbraMakeProfile(ivec2 ij, out UmbraProfile p) {
  float h = texelFetch(umbraHeights, ij, 0).r;
  h = h > umbraNoData ? h : umbraHeightAt(vec2(ij), vec2(0.0), 0.0, 0.0);  // (the CPU uses the 3 x 3 mean; tests avoid it)
  return umbraMakeProfileAt(vec2(ij), h, p);
}

float umbraMipMax(int level, ivec2 block) {
  return texelFetch(umbraMipAtlas, ivec2(block.x, umbraMipRow[level] + block.y), 0).r;
}

// Bilinear heights along one cell: a parabola through (sa, ha), (mid, hm), (sb, hb).
float umbraParabola(vec4 cell, vec3 h, float s) {  // cell = (centre, half, -, -)
  float u = (s - cell.x) / cell.y;
  return h.y + 0.5 * (h.z - h.x) * u + 0.5 * (h.x + h.z - 2.0 * h.y) * u * u;
}

// Cell by cell (SoftShadow.cpp cellSearch): in each cell the footprint crosses, the
// bilinear surface's highest elevation, at the cell's end and where the tangent of the
// elevation is stationary (s^2 = alpha / (gamma - k)).
float umbraHorizonCells(UmbraProfile p) {
  float hi = p.e + umbraSunRadius;
  float best = umbraTerrainElevation(p, umbraStartTexels);
  float k = umbraSpacingM * umbraSpacingM / (2.0 * (umbraRadiusM + p.hp));
  float s = umbraStartTexels;
  for (int guard = 0; guard < 512 && s < p.sEnd && best < hi; ++guard) {
    float next = max(min(p.sEnd, s + umbraToNextLine(p.g0 + s * p.dir, p.dir)), s + 1e-4);
    ivec2 c = clamp(ivec2(floor(p.g0 + 0.5 * (s + next) * p.dir)), ivec2(0), umbraGridSize - 2);
    vec4 corners = umbraCellCorners(c);
    float h00 = corners.x, h10 = corners.y, h01 = corners.z, h11 = corners.w;
    if (min(min(h00, h10), min(h01, h11)) <= umbraNoData) {
      best = max(best, umbraTerrainElevation(p, next));
    } else {
      // z(s) = e + ax fx + ay fy + x fx fy relative to the receiver, fx = fx0 + dir.x s.
      float e = h00 - p.hp, ax = h10 - h00, ay = h01 - h00, x = (h00 - h10) - (h01 - h11);
      vec2 f0 = p.g0 - vec2(c);
      vec2 f = f0 + next * p.dir;
      best = max(best, umbraElevation(p, umbraAngle(p, next), e + ax * f.x + ay * f.y + x * f.x * f.y));
      float alpha = e + ax * f0.x + ay * f0.y + x * f0.x * f0.y, gamma = x * p.dir.x * p.dir.y;
      if (alpha < 0.0 && gamma - k < 0.0) {
        float sPeak = sqrt(alpha / (gamma - k));
        if (sPeak > s && sPeak < next) {
          f = f0 + sPeak * p.dir;
          best = max(best, umbraElevation(p, umbraAngle(p, sPeak), e + ax * f.x + ay * f.y + x * f.x * f.y));
        }
      }
    }
    s = next;
  }
  return best;
}

// Algorithm 1 (see SoftShadow.cpp MipmapSearch): the highest horizon along the footprint.
float umbraHorizonDP(UmbraProfile p) {
  float lo = p.e - umbraSunRadius, hi = p.e + umbraSunRadius;
  float best = umbraTerrainElevation(p, umbraStartTexels);
  int top = clamp(umbraLevels - 1, 0, umbraMipLevels - 1);
  float block = exp2(float(top));
  vec2 cells = vec2(umbraGridSize - 1);
  // Explicit stacks: mip texels (level, bi, bj | sa, sb) and, below a texel, cell pieces.
  ivec3 nodeI[64];
  vec2 nodeS[64];
  vec3 pieceS[32];  // (sa, sb, depth)
  float s = umbraStartTexels;
  for (int guard = 0; guard < 100000 && s < p.sEnd && best < hi; ++guard) {
    vec2 g = p.g0 + s * p.dir;
    ivec2 bij;
    for (int k = 0; k < 2; ++k) {
      float q = g[k] / block;
      int b = int(floor(q));
      if (q == float(b) && p.dir[k] < 0.0) --b;
      bij[k] = clamp(b, 0, (k == 0 ? umbraMipWidth[top] : umbraMipHeight[top]) - 1);
    }
    float sa = s, sb = p.sEnd;
    vec2 lo2 = vec2(bij) * block, hi2 = min(vec2(bij + 1) * block, cells);
    bool inside = umbraClip(p, lo2, hi2, sa, sb);
    float next = inside ? sb : s;
    int n = 0;
    if (inside) { nodeI[0] = ivec3(top, bij); nodeS[0] = vec2(s, sb); n = 1; }
    while (n > 0 && best < hi) {
      --n;
      ivec3 node = nodeI[n];
      vec2 seg = nodeS[n];
      float hMax = umbraMipMax(node.x, node.yz);
      if (hMax <= umbraNoData) continue;
      if (umbraElevationBound(p, seg.x, seg.y, hMax - p.hp) <= max(best, lo)) continue;
      if (node.x == 0) {
        float mid = 0.5 * (seg.x + seg.y);
        vec3 h = vec3(umbraHeightAt(p.g0, p.dir, seg.x, p.hp), umbraHeightAt(p.g0, p.dir, mid, p.hp),
                      umbraHeightAt(p.g0, p.dir, seg.y, p.hp));  // relative to the receiver
        if (min(h.x, min(h.y, h.z)) <= umbraNoData) { best = max(best, umbraTerrainElevation(p, seg.y)); continue; }
        vec4 cell = vec4(mid, 0.5 * (seg.y - seg.x), 0.0, 0.0);
        float curvature = h.x + h.z - 2.0 * h.y;
        int m = 1;
        pieceS[0] = vec3(seg, 0.0);
        while (m > 0) {
          --m;
          vec3 piece = pieceS[m];
          float top2 = max(umbraParabola(cell, h, piece.x), umbraParabola(cell, h, piece.y));
          if (curvature < 0.0) {
            float sv = cell.x - 0.5 * (h.z - h.x) / curvature * cell.y;
            if (sv > piece.x && sv < piece.y) top2 = max(top2, umbraParabola(cell, h, sv));
          }
          float bound = umbraElevationBound(p, piece.x, piece.y, top2);
          if (bound <= max(best, lo)) continue;
          best = max(best, umbraElevation(p, umbraAngle(p, piece.y), umbraParabola(cell, h, piece.y)));
          if (bound - best <= umbraToleranceRad || piece.z >= 12.0 || best >= hi || m > 29) continue;
          float pm = 0.5 * (piece.x + piece.y);
          pieceS[m++] = vec3(pm, piece.y, piece.z + 1.0);  // the nearer half on top
          pieceS[m++] = vec3(piece.x, pm, piece.z + 1.0);
        }
        continue;
      }
      // Children the footprint crosses, pushed far first so that the nearest comes next.
      int level = node.x - 1;
      float size = exp2(float(level));
      ivec3 ci[4];
      vec2 cs[4];
      int c = 0;
      for (int dj = 0; dj < 2; ++dj)
        for (int di = 0; di < 2; ++di) {
          ivec2 child = 2 * node.yz + ivec2(di, dj);
          if (child.x >= umbraMipWidth[level] || child.y >= umbraMipHeight[level]) continue;
          float ca = seg.x, cb = seg.y;
          if (umbraClip(p, vec2(child) * size, min(vec2(child + 1) * size, cells), ca, cb)) {
            ci[c] = ivec3(level, child);
            cs[c] = vec2(ca, cb);
            ++c;
          }
        }
      for (int k = 1; k < c; ++k)
        for (int q = k; q > 0 && cs[q].x < cs[q - 1].x; --q) {
          ivec3 ti = ci[q]; ci[q] = ci[q - 1]; ci[q - 1] = ti;
          vec2 ts = cs[q]; cs[q] = cs[q - 1]; cs[q - 1] = ts;
        }
      for (int k = c - 1; k >= 0 && n < 64; --k) { nodeI[n] = ci[k]; nodeS[n] = cs[k]; ++n; }
    }
    s = max(next, s + 1e-6);
  }
  return best;
}

// eclipse::visibleFractionAboveHorizon(LimbDarkened): the disc above a chord d radii below
// its centre, from the smaller cap.
float umbraCapFraction(float h, float u) {
  float a = 2.0 * asin(sqrt(0.5 * h));
  float x = 2.0 * a;
  float x2 = x * x;
  float xMinusSin = x < 0.05 ? x * x2 / 6.0 * (1.0 - x2 / 20.0 * (1.0 - x2 / 42.0)) : x - sin(x);
  float area = 0.5 * xMinusSin;
  return ((1.0 - u) * area + 1.5707963 * u * h * h * (1.0 - h / 3.0)) / (3.14159265 * (1.0 - u / 3.0));
}

float umbraDiscFraction(float d, float u) {
  if (!(d > -1.0)) return 0.0;
  if (d >= 1.0) return 1.0;
  return d <= 0.0 ? umbraCapFraction(1.0 + d, u) : 1.0 - umbraCapFraction(1.0 - d, u);
}

vec2 umbraShadowOfProfile(UmbraProfile p) {
  float horizon = umbraHorizonDP(p);
  return vec2(umbraDiscFraction((p.e - horizon) / umbraSunRadius, umbraLimbDarkening), horizon);
}

// The visible fraction of the Sun at DEM sample ij (vec2: fraction, horizon elevation).
vec2 umbraTerrainShadow(ivec2 ij) {
  UmbraProfile p;
  if (!umbraMakeProfile(ij, p)) return vec2(p.e > 0.0 ? 1.0 : 0.0, -1e30);
  return umbraShadowOfProfile(p);
}

// The same for a receiver at grid coordinates g and height hp (terrain::horizonTowardsSunAt).
vec2 umbraTerrainShadowAt(vec2 g, float hp) {
  UmbraProfile p;
  if (!umbraMakeProfileAt(g, hp, p)) return vec2(p.e > 0.0 ? 1.0 : 0.0, -1e30);
  return umbraShadowOfProfile(p);
}
