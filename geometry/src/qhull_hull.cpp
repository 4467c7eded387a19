// The Qhull wrapper (see qhull_hull.h): one Qhull run per call, its diagnostics captured in memory
// and put into the exception on failure, its memory freed on every path.

#include "deepcheck/geometry/qhull_hull.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <csetjmp>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <utility>

extern "C" {
#include <libqhull_r/qhull_ra.h>
}

namespace deepcheck::geometry {
namespace {

/// Longest part of Qhull's diagnostics kept in an exception message (characters).
constexpr std::size_t kMaxMessage = 4000;

/// Qhull's error stream: an in-memory stream whose text goes into the exception on failure.
class MessageStream {
 public:
  MessageStream() : file_(open_memstream(&buffer_, &size_)) {
    if (file_ == nullptr) file_ = std::tmpfile();
    if (file_ == nullptr) file_ = std::fopen("/dev/null", "w");
  }
  ~MessageStream() {
    if (file_ != nullptr) std::fclose(file_);
    std::free(buffer_);
  }
  MessageStream(const MessageStream&) = delete;
  MessageStream& operator=(const MessageStream&) = delete;

  std::FILE* file() const { return file_; }

  /// What Qhull wrote, trimmed (empty when nothing could be captured).
  std::string text() {
    if (file_ == nullptr) return {};
    std::fflush(file_);
    std::string out;
    if (buffer_ != nullptr) {
      out.assign(buffer_, std::min(size_, kMaxMessage));
    } else {  // the temporary-file fallback
      std::rewind(file_);
      char chunk[512];
      std::size_t got = 0;
      while ((got = std::fread(chunk, 1, sizeof chunk, file_)) > 0 && out.size() < kMaxMessage) {
        out.append(chunk, got);
      }
    }
    while (!out.empty() && (out.back() == '\n' || out.back() == ' ')) out.pop_back();
    return out;
  }

 private:
  char* buffer_ = nullptr;
  std::size_t size_ = 0;
  std::FILE* file_ = nullptr;
};

[[noreturn]] void badCoordinate(double x, int point, int axis, const std::string& name) {
  char value[32];
  std::snprintf(value, sizeof value, "%.17g", x);
  throw std::invalid_argument(name + ": point " + std::to_string(point) + " coordinate " + "xyz"[axis] + " = " + value +
                              " is " + (std::isfinite(x) ? "out of Qhull's range (|value| > 1e+100)" : "non-finite"));
}

std::string optionString(const QhullOptions& options) {
  // Pp: precision problems are not reported as warnings (they are handled by the callers' checks
  // or reported through QhullError when Qhull gives up).
  std::string s = "qhull Pp";
  if (options.searchAllPoints) s += " Qs";
  if (options.triangulate) s += " Qt";
  if (options.mergeDistance >= 0.0) {
    char merge[40];
    std::snprintf(merge, sizeof merge, " C-%.17g", options.mergeDistance);
    s += merge;
  }
  return s;
}

/// Makes the loop counter-clockwise about `normal` (Newell's area vector against it): reversed,
/// or for a triangle of a triangulated hull its last two corners swapped (so that it still starts
/// at Qhull's first vertex).
void orientLoop(std::vector<int>& loop, const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& normal,
                bool triangulated) {
  Eigen::Vector3d area = Eigen::Vector3d::Zero();
  const Eigen::Vector3d& origin = points[loop[0]];
  for (std::size_t i = 1; i + 1 < loop.size(); ++i) {
    area += (points[loop[i]] - origin).cross(points[loop[i + 1]] - origin);
  }
  if (!(area.dot(normal) < 0.0)) return;
  if (triangulated && loop.size() == 3) std::swap(loop[1], loop[2]);
  else std::reverse(loop.begin(), loop.end());
}

/// Reads Qhull's facets and vertices into `out`. Returns Qhull's error code (0: fine); a point id
/// Qhull should not produce sets *badId.
int collectFacets(qhT* qh, int numPoints, QhullHull& out, bool* badId) {
  // qh_facet3vertex may report an error through longjmp: only trivially destructible locals live
  // between the setjmp and the calls below, and `out` is only appended to.
  const int code = setjmp(qh->errexit);
  if (code != 0) return code;
  qh->NOerrexit = False;
  vertexT* vertex;
  vertexT** vertexp;
  facetT* facet;
  FORALLvertices {
    const int id = qh_pointid(qh, vertex->point);
    if (id < 0 || id >= numPoints) *badId = true;
    out.vertices.push_back(id);
  }
  FORALLfacets {
    // Triangles (option Qt) keep Qhull's own vertex order; other facets are read around.
    const bool triangle = qh->TRIangulate && facet->simplicial;
    setT* vertices = triangle ? facet->vertices : qh_facet3vertex(qh, facet);
    out.loops.emplace_back();
    FOREACHvertex_(vertices) {
      const int id = qh_pointid(qh, vertex->point);
      if (id < 0 || id >= numPoints) *badId = true;
      out.loops.back().push_back(id);
    }
    if (!triangle) qh_settempfree(qh, &vertices);
    out.normals.emplace_back(facet->normal[0], facet->normal[1], facet->normal[2]);
    out.offsets.push_back(-facet->offset);
  }
  qh->NOerrexit = True;
  return 0;
}

}  // namespace

QhullHull qhullHull(const std::vector<Eigen::Vector3d>& points, const QhullOptions& options, const std::string& name) {
  const int n = static_cast<int>(points.size());
  if (n < kQhullMinPoints) {
    throw QhullError(name + ": a 3-d hull needs at least " + std::to_string(kQhullMinPoints) + " points, got " +
                     std::to_string(n));
  }
  std::vector<coordT> coords(3 * points.size());
  for (int i = 0; i < n; ++i) {
    for (int c = 0; c < 3; ++c) {
      if (!(std::abs(points[i][c]) <= kQhullMaxCoordinate)) badCoordinate(points[i][c], i, c, name);
      coords[3 * i + c] = points[i][c];
    }
  }
  MessageStream messages;
  std::string flags = optionString(options);
  QhullHull out;
  bool badId = false;
  qhT qhData;
  qhT* qh = &qhData;
  qh_zero(qh, messages.file());
  int code = qh_new_qhull(qh, 3, n, coords.data(), False, flags.data(), nullptr, messages.file());
  if (code == 0) code = collectFacets(qh, n, out, &badId);
  qh_freeqhull(qh, !qh_ALL);
  int curLong = 0;
  int totLong = 0;
  qh_memfreeshort(qh, &curLong, &totLong);
  if (code != 0) {
    throw QhullError(name + ": Qhull failed on " + std::to_string(n) + " points (exit code " + std::to_string(code) +
                     "): " + messages.text());
  }
  if (badId) throw QhullError(name + ": Qhull returned an unknown point id");
  for (std::size_t f = 0; f < out.loops.size(); ++f) {
    orientLoop(out.loops[f], points, out.normals[f], options.triangulate);
  }
  return out;
}

}  // namespace deepcheck::geometry
