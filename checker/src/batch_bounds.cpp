// The bound stage of World::isFreeBatch (batch_bounds.h): link spheres, then piece spheres and
// oriented boxes, against the world pieces the broad phase finds near the union of the lanes'
// link spheres, then the self pairs likewise; a lane stays certified while every test finds it
// apart. certifyAvx2 is flattened (every call in it inlined), so the helpers shared with the
// baseline build are compiled for AVX2 there.

#include "batch_bounds.h"

#include "batch_speeds.h"
#include "world_queries_internal.h"

#include <immintrin.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

namespace deepcheck::checker::detail {
namespace {

/// The double lanes of each build.
template <bool kAvx2>
using LanesOf = std::conditional_t<kAvx2, Avx2Lanes, BaselineLanes>;

/// A world piece's box in floats, and its largest |coordinate| (its part of the test scale).
struct FloatBox {
  float lo[3], hi[3];
  float mag;
};

FloatBox floatBox(const Aabb& box) {
  FloatBox b;
  for (int k = 0; k < 3; ++k) {
    b.lo[k] = static_cast<float>(box.lo[k]);
    b.hi[k] = static_cast<float>(box.hi[k]);
  }
  b.mag = static_cast<float>(std::max(box.lo.cwiseAbs().maxCoeff(), box.hi.cwiseAbs().maxCoeff()));
  return b;
}

/// A world piece's oriented box in floats: its centre, its axes (axis[j][k]: world component k of
/// box axis j), its half extents, and its part of the test scale (obbScale).
struct FloatObb {
  float c[3], axis[3][3], half[3];
  float mag;
};

/// A world oriented box's half extent along world axis k.
double worldExtent(const Obb& box, int k) {
  double e = 0.0;
  for (int j = 0; j < 3; ++j) e += std::abs(box.R(k, j)) * box.half[j];
  return e;
}

/// A world oriented box's part of a test's scale: |centre| max norm + its extents along the world
/// axes.
double obbScale(const Obb& box) {
  return box.center.cwiseAbs().maxCoeff() + (worldExtent(box, 0) + worldExtent(box, 1) + worldExtent(box, 2));
}

FloatObb floatObb(const Obb& box) {
  FloatObb f;
  for (int j = 0; j < 3; ++j) {
    f.c[j] = static_cast<float>(box.center[j]);
    f.half[j] = static_cast<float>(box.half[j]);
    for (int k = 0; k < 3; ++k) f.axis[j][k] = static_cast<float>(box.R(k, j));
  }
  f.mag = static_cast<float>(obbScale(box));
  return f;
}

/// A point in every lane with its scale (a world piece's sphere centre).
void broadcast(const Eigen::Vector3d& p, double radius, LaneFloats& f) {
  f.x = LaneFloatV{} + static_cast<float>(p.x());
  f.y = LaneFloatV{} + static_cast<float>(p.y());
  f.z = LaneFloatV{} + static_cast<float>(p.z());
  f.scale = LaneFloatV{} + static_cast<float>(p.cwiseAbs().maxCoeff() + radius);
}

// --- the sphere tests, baseline and AVX2 ----------------------------------------------------
// A sphere against a world box, a world oriented box or other spheres. Each is: far when
// d2 > rho^2, rho = radius + k (scale terms), d2 the squared distance, every operation rounded to
// float in the same order in both versions (max(a, b) is a > b ? a : b, as _mm256_max_ps).

inline float outside(float lo, float hi, float x) {
  const float a = lo - x;
  const float b = x - hi;
  const float m = a > b ? a : b;
  return m > 0.0f ? m : 0.0f;
}

/// Lanes whose sphere (p, r) lies beyond the box.
inline std::uint32_t farBaseline(const LaneFloats& p, float r, const FloatBox& b, float k) {
  std::uint32_t far = 0;
  for (int l = 0; l < kLanes; ++l) {
    const float ex = outside(b.lo[0], b.hi[0], p.x[l]);
    const float ey = outside(b.lo[1], b.hi[1], p.y[l]);
    const float ez = outside(b.lo[2], b.hi[2], p.z[l]);
    const float d2 = (ex * ex + ey * ey) + ez * ez;
    const float rho = r + k * (p.scale[l] + b.mag);
    far |= static_cast<std::uint32_t>(d2 > rho * rho) << l;
  }
  return far;
}

/// Lanes whose spheres (p, .) and (q, .) with radii summing to r are apart.
inline std::uint32_t farBaseline(const LaneFloats& p, float r, const LaneFloats& q, float k) {
  std::uint32_t far = 0;
  for (int l = 0; l < kLanes; ++l) {
    const float dx = p.x[l] - q.x[l];
    const float dy = p.y[l] - q.y[l];
    const float dz = p.z[l] - q.z[l];
    const float d2 = (dx * dx + dy * dy) + dz * dz;
    const float rho = r + k * (p.scale[l] + q.scale[l]);
    far |= static_cast<std::uint32_t>(d2 > rho * rho) << l;
  }
  return far;
}

/// Lanes whose sphere (p, r) lies beyond the oriented box: the point's excess over the half
/// extents along each box axis.
inline std::uint32_t farBaseline(const LaneFloats& p, float r, const FloatObb& b, float k) {
  std::uint32_t far = 0;
  for (int l = 0; l < kLanes; ++l) {
    const float dx = p.x[l] - b.c[0];
    const float dy = p.y[l] - b.c[1];
    const float dz = p.z[l] - b.c[2];
    float e[3];
    for (int j = 0; j < 3; ++j) {
      const float t = (dx * b.axis[j][0] + dy * b.axis[j][1]) + dz * b.axis[j][2];
      const float minus = 0.0f - t;
      const float a = (t > minus ? t : minus) - b.half[j];
      e[j] = a > 0.0f ? a : 0.0f;
    }
    const float d2 = (e[0] * e[0] + e[1] * e[1]) + e[2] * e[2];
    const float rho = r + k * (p.scale[l] + b.mag);
    far |= static_cast<std::uint32_t>(d2 > rho * rho) << l;
  }
  return far;
}

// The AVX2 versions, inlined into certifyAvx2.
#define DC_AVX2 __attribute__((target("avx2"))) inline

DC_AVX2 __m256 outsideAvx2(float lo, float hi, __m256 x) {
  const __m256 m = _mm256_max_ps(_mm256_sub_ps(_mm256_set1_ps(lo), x), _mm256_sub_ps(x, _mm256_set1_ps(hi)));
  return _mm256_max_ps(m, _mm256_setzero_ps());
}

DC_AVX2 std::uint32_t farMask(__m256 d2, __m256 rho) {
  return static_cast<std::uint32_t>(_mm256_movemask_ps(_mm256_cmp_ps(d2, _mm256_mul_ps(rho, rho), _CMP_GT_OQ)));
}

DC_AVX2 __m256 squaredNorm(__m256 x, __m256 y, __m256 z) {
  return _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(x, x), _mm256_mul_ps(y, y)), _mm256_mul_ps(z, z));
}

DC_AVX2 std::uint32_t farAvx2(const LaneFloats& p, float r, const FloatBox& b, float k) {
  const __m256 ex = outsideAvx2(b.lo[0], b.hi[0], p.x);
  const __m256 ey = outsideAvx2(b.lo[1], b.hi[1], p.y);
  const __m256 ez = outsideAvx2(b.lo[2], b.hi[2], p.z);
  const __m256 scale = _mm256_add_ps(p.scale, _mm256_set1_ps(b.mag));
  const __m256 rho = _mm256_add_ps(_mm256_set1_ps(r), _mm256_mul_ps(_mm256_set1_ps(k), scale));
  return farMask(squaredNorm(ex, ey, ez), rho);
}

DC_AVX2 std::uint32_t farAvx2(const LaneFloats& p, float r, const LaneFloats& q, float k) {
  const __m256 dx = _mm256_sub_ps(p.x, q.x);
  const __m256 dy = _mm256_sub_ps(p.y, q.y);
  const __m256 dz = _mm256_sub_ps(p.z, q.z);
  const __m256 scale = _mm256_add_ps(p.scale, q.scale);
  const __m256 rho = _mm256_add_ps(_mm256_set1_ps(r), _mm256_mul_ps(_mm256_set1_ps(k), scale));
  return farMask(squaredNorm(dx, dy, dz), rho);
}

DC_AVX2 std::uint32_t farAvx2(const LaneFloats& p, float r, const FloatObb& b, float k) {
  const __m256 dx = _mm256_sub_ps(p.x, _mm256_set1_ps(b.c[0]));
  const __m256 dy = _mm256_sub_ps(p.y, _mm256_set1_ps(b.c[1]));
  const __m256 dz = _mm256_sub_ps(p.z, _mm256_set1_ps(b.c[2]));
  __m256 e[3];
  for (int j = 0; j < 3; ++j) {
    const __m256 t = _mm256_add_ps(
        _mm256_add_ps(_mm256_mul_ps(dx, _mm256_set1_ps(b.axis[j][0])), _mm256_mul_ps(dy, _mm256_set1_ps(b.axis[j][1]))),
        _mm256_mul_ps(dz, _mm256_set1_ps(b.axis[j][2])));
    const __m256 a = _mm256_sub_ps(_mm256_max_ps(t, _mm256_sub_ps(_mm256_setzero_ps(), t)), _mm256_set1_ps(b.half[j]));
    e[j] = _mm256_max_ps(a, _mm256_setzero_ps());
  }
  const __m256 scale = _mm256_add_ps(p.scale, _mm256_set1_ps(b.mag));
  const __m256 rho = _mm256_add_ps(_mm256_set1_ps(r), _mm256_mul_ps(_mm256_set1_ps(k), scale));
  return farMask(squaredNorm(e[0], e[1], e[2]), rho);
}

/// Lanes whose sphere (p, r) lies beyond `other` (a FloatBox, a FloatObb, or spheres whose radii
/// r already sums), by the test of the build that runs.
template <bool kAvx2, class Other>
inline std::uint32_t beyond(const LaneFloats& p, double r, const Other& other) {
  const float k = static_cast<float>(tol::kBatchBoundRelative);
  if constexpr (kAvx2) {
    return farAvx2(p, static_cast<float>(r), other, k);
  } else {
    return farBaseline(p, static_cast<float>(r), other, k);
  }
}

// --- the traversal --------------------------------------------------------------------------

/// Float copies of the posed centres with their scales (|c| max norm + radius + chain length).
/// The eight lanes of d as floats.
template <class L>
inline void toFloat(const L& d, LaneFloatV& out) {
  using Part = float __attribute__((vector_size(4 * sizeof(float))));
  if constexpr (L::kWidth == 4) {
    out = __builtin_shufflevector(__builtin_convertvector(d.h[0], Part), __builtin_convertvector(d.h[1], Part), 0, 1, 2,
                                  3, 4, 5, 6, 7);
  } else {
    for (int l = 0; l < kLanes; ++l) out[l] = static_cast<float>(d[l]);
  }
}

template <class L>
void toFloats(const LanePointT<L>& c, double radius, const L& chain, LaneFloats& f) {
  toFloat(c.x, f.x);
  toFloat(c.y, f.y);
  toFloat(c.z, f.z);
  toFloat(laneMax(laneMax(laneAbs(c.x), laneAbs(c.y)), laneAbs(c.z)) + radius + chain, f.scale);
}

/// The link geometries' centres in floats; a new stamp for the pieces'.
template <class L>
void linksToFloats(const RobotData& robot, BatchScratch& sc) {
  const BatchPosesT<L>& poses = sc.poses<L>();
  sc.linkF.resize(robot.links.size());
  for (std::size_t g = 0; g < robot.links.size(); ++g) {
    toFloats(poses.linkCenter[g], robot.links[g].radius, poses.chainLength, sc.linkF[g]);
  }
  if (sc.pieceStamp.size() != robot.pieces.size() || ++sc.stamp == 0) {
    sc.pieceStamp.assign(robot.pieces.size(), 0);
    sc.boxStamp.assign(robot.pieces.size(), 0);
    sc.pieceF.resize(robot.pieces.size());
    sc.stamp = 1;
  }
  // Each build has its own boxes: a context may run both (the tests' baseline switch).
  if (sc.boxes<L>().size() != robot.pieces.size()) sc.boxes<L>().resize(robot.pieces.size());
}

/// Robot piece i's centre in floats (posed once per batch).
template <class L>
inline const LaneFloats& pieceFloats(const RobotData& robot, int i, BatchScratch& sc) {
  if (sc.pieceStamp[i] != sc.stamp) {
    const RobotPiece& p = robot.pieces[i];
    const BatchPosesT<L>& poses = sc.poses<L>();
    LanePointT<L> c;
    posePoint(poses.links[p.link], p.center_L, c);
    toFloats(c, p.sphereRadius, poses.chainLength, sc.pieceF[i]);
    sc.pieceStamp[i] = sc.stamp;
  }
  return sc.pieceF[i];
}

/// Robot piece i's oriented box in the world, every lane (posed once per batch).
template <class L>
inline const LaneBoxT<L>& pieceBox(const RobotData& robot, int i, BatchScratch& sc) {
  LaneBoxT<L>& b = sc.boxes<L>()[i];
  if (sc.boxStamp[i] == sc.stamp) return b;
  const RobotPiece& p = robot.pieces[i];
  const BatchPosesT<L>& poses = sc.poses<L>();
  const LanePoseT<L>& X = poses.links[p.link];
  LanePointT<L> c;
  posePoint(X, p.obb_L.center, c);
  b.c[0] = c.x;
  b.c[1] = c.y;
  b.c[2] = c.z;
  L extents{};
  for (int k = 0; k < 3; ++k) {
    b.e[k] = L{};
    for (int j = 0; j < 3; ++j) {
      L& axis = b.R[3 * k + j];
      axis = X.R[3 * k] * p.obb_L.R(0, j) + X.R[3 * k + 1] * p.obb_L.R(1, j) + X.R[3 * k + 2] * p.obb_L.R(2, j);
      b.e[k] += laneAbs(axis) * p.obb_L.half[j];
    }
    extents += b.e[k];
  }
  b.scale = laneMax(laneMax(laneAbs(c.x), laneAbs(c.y)), laneAbs(c.z)) + extents + poses.chainLength;
  sc.boxStamp[i] = sc.stamp;
  return b;
}

/// Lanes whose oriented box b lies beyond the world box along a world axis, by `clear` and
/// tol::kBatchBoundRelative of the scale (doubles: both builds compute the same bits).
template <class L>
inline std::uint32_t obbApart(const LaneBoxT<L>& b, const Aabb& box, double boxMag, double clear) {
  const L margin = (b.scale + boxMag) * tol::kBatchBoundRelative + clear;
  typename L::Mask apart{};
  for (int k = 0; k < 3; ++k) {
    apart = apart | ((b.c[k] - b.e[k]) - box.hi[k] > margin) | (box.lo[k] - (b.c[k] + b.e[k]) > margin);
  }
  return apart.bits();
}

/// A world piece's oriented box in every lane, with its scale (obbScale).
template <class L>
LaneBoxT<L> worldBox(const Obb& box) {
  LaneBoxT<L> b;
  for (int k = 0; k < 3; ++k) {
    b.c[k] = L::all(box.center[k]);
    for (int j = 0; j < 3; ++j) b.R[3 * k + j] = L::all(box.R(k, j));
    b.e[k] = L::all(worldExtent(box, k));
  }
  b.scale = L::all(obbScale(box));
  return b;
}

/// Lanes where robot pieces i and j (boxes a and b) are apart along one of the 15 axes of the
/// separating-axis test (obb.h), by `clear` and tol::kBatchBoundRelative of their scales (doubles). An
/// edge-product axis is not normalized: its gap is shrunk by its length (at most 1), so the
/// margin asks for more there, and nearly parallel edges never separate. Only the lanes in `need`
/// are asked about: when the six face normals separate all of them, the edge products are skipped
/// (the other lanes' bits may then miss an edge-product separation).
template <class L>
inline std::uint32_t obbsApart(const Eigen::Vector3d& ha, const LaneBoxT<L>& a, const Eigen::Vector3d& hb,
                               const LaneBoxT<L>& b, double clear, std::uint32_t need) {
  const L margin = (a.scale + b.scale) * tol::kBatchBoundRelative + clear;
  const L t[3] = {b.c[0] - a.c[0], b.c[1] - a.c[1], b.c[2] - a.c[2]};
  L C[9], absC[9];  // a_i . b_j
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      C[3 * i + j] = a.R[i] * b.R[j] + a.R[3 + i] * b.R[3 + j] + a.R[6 + i] * b.R[6 + j];
      absC[3 * i + j] = laneAbs(C[3 * i + j]);
    }
  }
  L ta[3];  // t along a's axes
  typename L::Mask apart{};
  for (int i = 0; i < 3; ++i) {  // a's face normals
    ta[i] = t[0] * a.R[i] + t[1] * a.R[3 + i] + t[2] * a.R[6 + i];
    const L reach = ha[i] + absC[3 * i] * hb[0] + absC[3 * i + 1] * hb[1] + absC[3 * i + 2] * hb[2];
    apart = apart | (laneAbs(ta[i]) - reach > margin);
  }
  for (int j = 0; j < 3; ++j) {  // b's face normals
    const L d = laneAbs(t[0] * b.R[j] + t[1] * b.R[3 + j] + t[2] * b.R[6 + j]);
    const L reach = hb[j] + absC[j] * ha[0] + absC[3 + j] * ha[1] + absC[6 + j] * ha[2];
    apart = apart | (d - reach > margin);
  }
  if (const std::uint32_t faces = apart.bits(); (faces & need) == need) return faces;
  for (int i = 0; i < 3; ++i) {  // a_i x b_j
    const int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
    for (int j = 0; j < 3; ++j) {
      const int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
      const L d = laneAbs(ta[i2] * C[3 * i1 + j] - ta[i1] * C[3 * i2 + j]);
      const L reach =
          ha[i1] * absC[3 * i2 + j] + ha[i2] * absC[3 * i1 + j] + hb[j1] * absC[3 * i + j2] + hb[j2] * absC[3 * i + j1];
      apart = apart | (d - reach > margin);
    }
  }
  return apart.bits();
}

/// Lanes of `open` where some piece pair of self pair sp is within `clear`: piece spheres not
/// apart and oriented boxes not apart along a face normal, by `clear` more.
template <bool kAvx2>
inline std::uint32_t selfPiecesNear(const RobotData& robot, const SelfPair& sp, double clear, BatchScratch& sc,
                                    std::uint32_t open) {
  const LinkGeometry& la = robot.links[sp.a];
  const LinkGeometry& lb = robot.links[sp.b];
  std::uint32_t near = 0;
  for (int i = la.firstPiece; i < la.firstPiece + la.numPieces; ++i) {
    for (int j = lb.firstPiece; j < lb.firstPiece + lb.numPieces; ++j) {
      const double r = robot.pieces[i].sphereRadius + robot.pieces[j].sphereRadius + clear;
      std::uint32_t pairNear =
          ~beyond<kAvx2>(pieceFloats<LanesOf<kAvx2>>(robot, i, sc), r, pieceFloats<LanesOf<kAvx2>>(robot, j, sc)) &
          open;
      if (pairNear != 0) {
        pairNear &= ~obbsApart(robot.pieces[i].obb_L.half, pieceBox<LanesOf<kAvx2>>(robot, i, sc),
                               robot.pieces[j].obb_L.half, pieceBox<LanesOf<kAvx2>>(robot, j, sc), clear, pairNear);
      }
      near |= pairNear;
      if (near == open) return near;
    }
  }
  return near;
}

/// The lanes set in `bits`, as a mask.
template <class L>
inline typename L::Mask maskOf(std::uint32_t bits) {
  typename L::Mask m;
  for (int l = 0; l < kLanes; ++l) m.h[l / L::kWidth][l % L::kWidth] = (bits >> l & 1u) != 0 ? -1 : 0;
  return m;
}

/// The box around the spheres (c, radius) of the lanes in `open`, each grown by
/// tol::kBatchBoundRelative of its scale (in doubles): a world box the broad phase does not find
/// near it lies beyond every one of those spheres by that much. The lanes in `open` have finite
/// poses; the others count as empty (infinite bounds), so they never widen it.
template <class L>
Aabb unionBox(const LanePointT<L>& c, double radius, const L& chain, std::uint32_t open) {
  const L r =
      radius + (laneMax(laneMax(laneAbs(c.x), laneAbs(c.y)), laneAbs(c.z)) + radius + chain) * tol::kBatchBoundRelative;
  const typename L::Mask in = maskOf<L>(open);
  const double inf = std::numeric_limits<double>::infinity();
  const L* centre[3] = {&c.x, &c.y, &c.z};
  Aabb box;
  for (int k = 0; k < 3; ++k) {
    box.lo[k] = extremeLane(select(in, *centre[k] - r, L::all(inf)), false);
    box.hi[k] = extremeLane(select(in, *centre[k] + r, L::all(-inf)), true);
  }
  return box;
}

/// Lanes of `open` where some piece of link geometry g is within `clear` of world piece w: its
/// sphere grown by `clear` neither beyond w's box nor beyond w's sphere, and its oriented box not
/// beyond w's box by `clear`.
template <bool kAvx2>
inline std::uint32_t piecesNear(const RobotData& robot, int g, const WorldPiece& w, const FloatBox& b, double clear,
                                BatchScratch& sc, std::uint32_t open) {
  const LinkGeometry& lg = robot.links[g];
  LaneFloats wc;
  broadcast(w.center_W, w.sphereRadius, wc);
  std::uint32_t near = 0;
  std::optional<FloatObb> wf;                  // w's oriented box in floats, made once when needed
  std::optional<LaneBoxT<LanesOf<kAvx2>>> wb;  // ... and in doubles in every lane
  for (int i = lg.firstPiece; i < lg.firstPiece + lg.numPieces; ++i) {
    const double r = robot.pieces[i].sphereRadius + clear;
    const LaneFloats& p = pieceFloats<LanesOf<kAvx2>>(robot, i, sc);
    std::uint32_t pieceNear = ~(beyond<kAvx2>(p, r, b) | beyond<kAvx2>(p, r + w.sphereRadius, wc)) & open;
    if (pieceNear != 0) {
      if (!wf) wf = floatObb(w.obb_W);
      pieceNear &= ~beyond<kAvx2>(p, r, *wf);
    }
    if (pieceNear != 0) pieceNear &= ~obbApart(pieceBox<LanesOf<kAvx2>>(robot, i, sc), w.box, b.mag, clear);
    if (pieceNear != 0) {
      if (!wb) wb = worldBox<LanesOf<kAvx2>>(w.obb_W);
      pieceNear &= ~obbsApart(robot.pieces[i].obb_L.half, pieceBox<LanesOf<kAvx2>>(robot, i, sc), w.obb_W.half, *wb,
                              clear, pieceNear);
    }
    near |= pieceNear;
    if (near == open) break;
  }
  return near;
}

/// Lanes of `open` where link geometry g may come within `clear` of a world piece of kind `kind`.
template <bool kAvx2>
inline std::uint32_t worldBlocked(const Snapshot& s, PairKey::Kind kind, int g, double clear, BroadPhase broadPhase,
                                  BatchScratch& sc, std::uint32_t open) {
  const PieceSet& set = worldPieces(s, kind);
  if (set.pieces.empty()) return 0;
  const RobotData& robot = *s.robot;
  const double radius = robot.links[g].radius + clear;
  std::uint32_t blocked = 0;
  const BatchPosesT<LanesOf<kAvx2>>& poses = sc.poses<LanesOf<kAvx2>>();
  const Aabb query = unionBox(poses.linkCenter[g], radius, poses.chainLength, open);
  sc.candidates.clear();
  forEachOverlapping(set, broadPhase, query, [&](int wp) {
    if (!worldPairAllowed(s, kind, g, set.pieces[wp].body)) sc.candidates.push_back(wp);
    return false;
  });
  for (int wp : sc.candidates) {
    const WorldPiece& w = set.pieces[wp];
    const FloatBox b = floatBox(w.box);
    std::uint32_t near = ~beyond<kAvx2>(sc.linkF[g], radius, b) & open & ~blocked;
    if (near != 0) near = piecesNear<kAvx2>(robot, g, w, b, clear, sc, near);
    blocked |= near;
    if ((open & ~blocked) == 0) break;
  }
  return blocked;
}

/// True when the batch's grids may certify a pair along the lanes' sub-motions (at a margin
/// above 0): the batch has a motion and asks for no base clearance.
inline bool gridsCertifyAlong(const BatchMargins& margins) {
  return margins.dq != nullptr && margins.demand->base == 0.0;
}

/// True when self pair sp's grid certifies it for lane q, as Margins::gridCertifies does: free at
/// q when its margin is 0, free all along the lane's sub-motion when the motion asks for no base
/// clearance; otherwise only the pieces' distance can.
inline bool gridCertifies(const SelfPairGrid& grid, const Eigen::VectorXd& q, double clear,
                          const BatchMargins& margins) {
  if (clear == 0.0) return grid.certifiedFree(q);
  return gridsCertifyAlong(margins) && grid.certifiedFreeAlong(q, *margins.dq, margins.scale);
}

/// The box around every lane of qs in which the grids are asked first (BatchScratch::boxLower):
/// the lanes' smallest and largest values, less and plus the sub-motions' reach, scale |dq|, when
/// the batch has a motion (its grid tests at a margin of 0, of points only, then see a larger box
/// than they need: still every point they test).
void gridBox(const Eigen::Ref<const Eigen::MatrixXd>& qs, const BatchMargins& margins, BatchScratch& sc) {
  sc.boxLower = qs.rowwise().minCoeff();
  sc.boxUpper = qs.rowwise().maxCoeff();
  sc.boxReady = true;
  if (margins.dq == nullptr) return;
  for (Eigen::Index v = 0; v < qs.rows(); ++v) {  // each reach rounded as certifiedFreeAlong rounds it
    const double reach = margins.scale * std::abs((*margins.dq)[v]);
    sc.boxLower[v] -= reach;
    sc.boxUpper[v] += reach;
  }
}

/// True when self pair sp's grid certifies every lane of qs at once, as gridCertifies would lane
/// by lane: free over a box holding every lane's configuration and sub-motion. Lanes spread
/// along a motion far from the pair's contacts pass with one lookup instead of one per lane.
inline bool gridCertifiesAll(const SelfPairGrid& grid, const Eigen::Ref<const Eigen::MatrixXd>& qs, double clear,
                             const BatchMargins& margins, BatchScratch& sc) {
  if (clear != 0.0 && !gridsCertifyAlong(margins)) return false;
  if (!sc.boxReady) gridBox(qs, margins, sc);
  return grid.certifiedFreeWithin(sc.boxLower, sc.boxUpper);
}

/// Lanes of `open` where self pair sp may come within `clear`: link spheres not apart by it and
/// no grid certificate.
template <bool kAvx2>
inline std::uint32_t selfBlocked(const RobotData& robot, const SelfPair& sp, double clear, const BatchMargins& margins,
                                 const Eigen::Ref<const Eigen::MatrixXd>& qs, BatchScratch& sc, std::uint32_t open) {
  const double r = robot.links[sp.a].radius + robot.links[sp.b].radius + clear;
  std::uint32_t near = ~beyond<kAvx2>(sc.linkF[sp.a], r, sc.linkF[sp.b]) & open;
  if (near != 0 && sp.grid != nullptr && gridCertifiesAll(*sp.grid, qs, clear, margins, sc)) near = 0;
  if (near != 0 && sp.grid != nullptr) {
    for (int l = 0; l < static_cast<int>(qs.cols()); ++l) {
      if (!(near >> l & 1u)) continue;
      sc.q = qs.col(l);
      if (gridCertifies(*sp.grid, sc.q, clear, margins)) near &= ~(1u << l);
    }
  }
  return near == 0 ? 0 : selfPiecesNear<kAvx2>(robot, sp, clear, sc, near);
}

/// A margin grown by tol::kBatchBoundRelative of itself: its rounding to float is then covered,
/// as the coordinates' is by their scales. NaN when it is negative or not finite.
double grown(double m) {
  if (!(m >= 0.0 && m < std::numeric_limits<double>::infinity())) return std::numeric_limits<double>::quiet_NaN();
  return m * (1.0 + tol::kBatchBoundRelative);
}

/// Each link geometry's margin against the world, then each self pair's (Margins::worldUpper and
/// selfUpper), grown. False when one is negative or not finite (the bound stage then certifies
/// nothing, and the queries name the demand).
bool lanesMargins(const Snapshot& s, const BatchMargins& margins, std::vector<double>& out) {
  const RobotData& robot = *s.robot;
  out.assign(robot.links.size() + s.selfPairs.size(), 0.0);
  if (margins.demand == nullptr) return true;
  const ClearanceDemand& d = *margins.demand;
  for (std::size_t g = 0; g < robot.links.size(); ++g) out[g] = d.base + margins.scale * d.link[robot.links[g].link];
  for (std::size_t i = 0; i < s.selfPairs.size(); ++i) {
    const SelfPair& sp = s.selfPairs[i];
    out[robot.links.size() + i] = d.base + margins.scale * d.self(robot.links[sp.a].link, robot.links[sp.b].link);
  }
  for (double& m : out) {
    m = grown(m);
    if (std::isnan(m)) return false;
  }
  return true;
}

/// The margins of a motion's lanes from the posed bound over them (batch_speeds.h), grown: at most
/// the configuration-free ones, and costlier, so made only for the link geometries that those
/// leave near some lane, once per batch. Available when every lane is posed.
template <class L>
class PosedLaneMargins {
 public:
  PosedLaneMargins(const Snapshot& s, const BatchMargins& margins, bool allPosed, BatchScratch& sc)
      : s_(s), margins_(margins), sc_(sc), available_(allPosed && margins.demand != nullptr && margins.dq != nullptr) {
    if (available_) sc.speeds.assign(s.robot->links.size(), std::numeric_limits<double>::quiet_NaN());
  }
  bool available() const { return available_; }
  double world(std::size_t g) { return grown(margins_.demand->base + margins_.scale * speed(g)); }
  double self(const SelfPair& sp) {
    return grown(margins_.demand->base +
                 margins_.scale * (speed(static_cast<std::size_t>(sp.a)) + speed(static_cast<std::size_t>(sp.b))));
  }

 private:
  double speed(std::size_t g) {
    double& v = sc_.speeds[g];
    if (std::isnan(v)) {
      thread_local std::vector<SpeedTerm> terms;
      v = lanesPosedSpeed(*s_.robot, sc_.poses<L>(), *margins_.demand, *margins_.dq, margins_.scale, g, terms);
    }
    return v;
  }
  const Snapshot& s_;
  const BatchMargins& margins_;
  BatchScratch& sc_;
  bool available_;
};

template <bool kAvx2>
inline std::uint32_t certify(const Snapshot& s, BroadPhase broadPhase, const Eigen::Ref<const Eigen::MatrixXd>& qs,
                             BatchScratch& sc, const BatchMargins& margins) {
  const std::uint32_t lanes = (1u << qs.cols()) - 1u;
  // Without margins a blocked lane is left to isFree, and the tests stop for it; with margins
  // every lane is tested against every link geometry and self pair, so that a clearance test of a
  // blocked lane knows which ones need it (nearLanes: every one, until the tests say otherwise).
  const bool record = margins.demand != nullptr;
  if (record) sc.nearLanes.assign(s.robot->links.size() + s.selfPairs.size(), ~0u);
  std::uint32_t blocked = 0;
  for (int l = 0; l < static_cast<int>(qs.cols()); ++l) {
    if (!sc.poses<LanesOf<kAvx2>>().finite[l]) blocked |= 1u << l;
  }
  if (blocked == lanes) return 0;
  if (!lanesMargins(s, margins, sc.margins)) return 0;
  PosedLaneMargins<LanesOf<kAvx2>> posed(s, margins, blocked == 0, sc);
  sc.boxReady = false;
  const RobotData& robot = *s.robot;
  linksToFloats<LanesOf<kAvx2>>(robot, sc);
  const std::uint32_t unposed = blocked;  // lanes whose poses are not finite: near everything
  if (record) std::fill(sc.nearLanes.begin(), sc.nearLanes.end(), unposed);
  for (int g = static_cast<int>(robot.links.size()) - 1; g >= 0; --g) {
    const double clear = sc.margins[static_cast<std::size_t>(g)];
    for (PairKey::Kind kind : {PairKey::Kind::Scene, PairKey::Kind::Obstacle}) {
      const std::uint32_t open = lanes & ~(record ? unposed : blocked);
      std::uint32_t near = worldBlocked<kAvx2>(s, kind, g, clear, broadPhase, sc, open);
      // The lanes still near are tested again with the tighter margin, when it is.
      if (near != 0 && posed.available()) {
        const double tight = posed.world(static_cast<std::size_t>(g));
        if (tight < clear) near = worldBlocked<kAvx2>(s, kind, g, tight, broadPhase, sc, near);
      }
      blocked |= near;
      if (record) sc.nearLanes[static_cast<std::size_t>(g)] |= near;
      if (blocked == lanes && !record) return 0;
    }
  }
  for (std::size_t i = 0; i < s.selfPairs.size(); ++i) {
    const double clear = sc.margins[robot.links.size() + i];
    const std::uint32_t open = lanes & ~(record ? unposed : blocked);
    std::uint32_t near = selfBlocked<kAvx2>(robot, s.selfPairs[i], clear, margins, qs, sc, open);
    if (near != 0 && posed.available()) {
      const double tight = posed.self(s.selfPairs[i]);
      if (tight < clear) near = selfBlocked<kAvx2>(robot, s.selfPairs[i], tight, margins, qs, sc, near);
    }
    blocked |= near;
    if (record) sc.nearLanes[robot.links.size() + i] |= near;
    if (blocked == lanes && !record) return 0;
  }
  return lanes & ~blocked;
}

__attribute__((target("avx2"), flatten)) std::uint32_t certifyAvx2(const Snapshot& s, BroadPhase broadPhase,
                                                                   const Eigen::Ref<const Eigen::MatrixXd>& qs,
                                                                   BatchScratch& sc, const BatchMargins& margins) {
  return certify<true>(s, broadPhase, qs, sc, margins);
}

std::uint32_t certifyBaseline(const Snapshot& s, BroadPhase broadPhase, const Eigen::Ref<const Eigen::MatrixXd>& qs,
                              BatchScratch& sc, const BatchMargins& margins) {
  return certify<false>(s, broadPhase, qs, sc, margins);
}

}  // namespace

std::uint32_t batchCertifiedLanes(const Snapshot& s, BroadPhase broadPhase, const Eigen::Ref<const Eigen::MatrixXd>& qs,
                                  bool avx2, BatchScratch& scratch, const BatchMargins& margins) {
  return avx2 ? certifyAvx2(s, broadPhase, qs, scratch, margins) : certifyBaseline(s, broadPhase, qs, scratch, margins);
}

}  // namespace deepcheck::checker::detail
