// writeHtmlView: a ViewScene as JSON inside the page template of viewer/, with three.js, its
// OrbitControls and the viewer's JavaScript and CSS inlined (html_view.h).
//
// Bulk numbers (mesh vertices, piece edges, per-frame poses) are base64 of little-endian float32 /
// uint32 / float64 arrays: a third of the size of decimal text and decoded without parsing.

#include "deepcheck/viewer/html_view.h"

#include "deepcheck_viewer_assets.h"  // generated from viewer/ and libjs-three (viewer/CMakeLists.txt)

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <utility>
#include <string>
#include <vector>

namespace deepcheck::viewer {
namespace {

std::string base64(const void* data, std::size_t size) {
  static const char* const kDigits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  const auto* bytes = static_cast<const unsigned char*>(data);
  std::string out;
  out.reserve((size + 2) / 3 * 4);
  for (std::size_t i = 0; i < size; i += 3) {
    const unsigned b0 = bytes[i];
    const unsigned b1 = i + 1 < size ? bytes[i + 1] : 0u;
    const unsigned b2 = i + 2 < size ? bytes[i + 2] : 0u;
    const unsigned triple = (b0 << 16) | (b1 << 8) | b2;
    out += kDigits[(triple >> 18) & 63];
    out += kDigits[(triple >> 12) & 63];
    out += i + 1 < size ? kDigits[(triple >> 6) & 63] : '=';
    out += i + 2 < size ? kDigits[triple & 63] : '=';
  }
  return out;
}

template <class T>
std::string base64Of(const std::vector<T>& values) {
  static_assert(sizeof(float) == 4 && sizeof(double) == 8, "IEEE float32 / float64 expected");
  return '"' + base64(values.data(), values.size() * sizeof(T)) + '"';
}

/// A JSON string; '<' is escaped so that no "</script>" can end the data block.
std::string jsonString(const std::string& s) {
  std::string out = "\"";
  for (const char c : s) {
    const auto u = static_cast<unsigned char>(c);
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (c == '\n') {
      out += "\\n";
    } else if (u < 0x20 || c == '<' || c == '>' || c == '&') {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", u);
      out += buf;
    } else {
      out += c;
    }
  }
  return out + '"';
}

std::string number(double v) {
  if (!std::isfinite(v)) return "null";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

void requireFinite(const Eigen::Ref<const Eigen::MatrixXd>& m, const std::string& what) {
  if (!m.allFinite()) throw std::invalid_argument("writeHtmlView: " + what + " is not finite");
}

/// x y z qx qy qz qw of a pose.
void appendPose(const Eigen::Isometry3d& X, const std::string& what, std::vector<float>& out) {
  requireFinite(X.matrix(), what);
  const Eigen::Quaterniond q(X.linear());
  for (int i = 0; i < 3; ++i) out.push_back(static_cast<float>(X.translation()[i]));
  for (const double c : {q.x(), q.y(), q.z(), q.w()}) out.push_back(static_cast<float>(c));
}

std::string poseJson(const Eigen::Isometry3d& X, const std::string& what) {
  std::vector<float> p;
  appendPose(X, what, p);
  std::string out = "[";
  for (std::size_t i = 0; i < p.size(); ++i) out += (i ? "," : "") + number(p[i]);
  return out + "]";
}

std::string vectorJson(const Eigen::Vector3d& v) {
  return "[" + number(v.x()) + "," + number(v.y()) + "," + number(v.z()) + "]";
}

std::string shapeJson(const ViewShape& s, const std::string& what) {
  const robots::Geometry& g = s.geometry;
  std::string out = "{\"pose\":" + poseJson(s.X_BG, what + " pose") + ",\"type\":";
  switch (g.type) {
    case robots::GeometryType::Box:
      requireFinite(g.boxSize, what + " size");
      return out + "\"box\",\"size\":" + vectorJson(g.boxSize) + "}";
    case robots::GeometryType::Sphere:
      return out + "\"sphere\",\"radius\":" + number(g.radius) + "}";
    case robots::GeometryType::Cylinder:
      return out + "\"cylinder\",\"radius\":" + number(g.radius) + ",\"length\":" + number(g.length) + "}";
    case robots::GeometryType::Mesh:
      break;
  }
  if (!s.mesh) throw std::invalid_argument("writeHtmlView: " + what + " is a mesh without its triangles");
  std::vector<float> vertices;
  for (const Eigen::Vector3d& v : s.mesh->vertices) {
    requireFinite(v, what + " vertex");
    for (int i = 0; i < 3; ++i) vertices.push_back(static_cast<float>(v[i]));
  }
  std::vector<std::uint32_t> triangles;
  for (const auto& t : s.mesh->triangles) {
    for (const int i : t) {
      if (i < 0 || i >= static_cast<int>(s.mesh->vertices.size())) {
        throw std::invalid_argument("writeHtmlView: " + what + " has a triangle with vertex index " +
                                    std::to_string(i));
      }
      triangles.push_back(static_cast<std::uint32_t>(i));
    }
  }
  return out + "\"mesh\",\"vertices\":" + base64Of(vertices) + ",\"triangles\":" + base64Of(triangles) + "}";
}

/// All pieces of a body in one wireframe: vertices (body frame), edges, the first vertex of each
/// piece (for its colour), and spheres [x y z r] for point and segment cores with a radius.
std::string piecesJson(const std::vector<robots::CollisionPiece>& pieces, const std::string& what) {
  std::vector<float> vertices;
  std::vector<std::uint32_t> edges;
  std::vector<std::uint32_t> firsts;
  std::vector<float> spheres;
  for (const robots::CollisionPiece& p : pieces) {
    if (!p.core) throw std::invalid_argument("writeHtmlView: a piece of " + what + " has no core");
    const geometry::ConvexPolytope& core = *p.core;
    const auto first = static_cast<std::uint32_t>(vertices.size() / 3);
    firsts.push_back(first);
    for (int v = 0; v < core.numVertices(); ++v) {
      const Eigen::Vector3d x = p.X_LP * core.vertex(v);
      requireFinite(x, "a piece vertex of " + what);
      for (int i = 0; i < 3; ++i) vertices.push_back(static_cast<float>(x[i]));
      for (const int w : core.neighbors(v)) {
        if (v < w)
          edges.insert(edges.end(), {first + static_cast<std::uint32_t>(v), first + static_cast<std::uint32_t>(w)});
      }
      if (p.radius > 0.0 && core.numVertices() <= 2) {
        spheres.insert(spheres.end(), {static_cast<float>(x[0]), static_cast<float>(x[1]), static_cast<float>(x[2]),
                                       static_cast<float>(p.radius)});
      }
    }
  }
  return "{\"count\":" + std::to_string(pieces.size()) + ",\"vertices\":" + base64Of(vertices) +
         ",\"edges\":" + base64Of(edges) + ",\"firsts\":" + base64Of(firsts) + ",\"spheres\":" + base64Of(spheres) +
         "}";
}

void writeBodies(const ViewScene& scene, std::ostream& out) {
  out << "\"bodies\":[";
  for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
    const ViewBody& body = scene.bodies[b];
    const std::string what = "body '" + body.name + "'";
    if (body.track < -1 || body.track >= scene.numTracks) {
      throw std::invalid_argument("writeHtmlView: " + what + " follows track " + std::to_string(body.track) + " of " +
                                  std::to_string(scene.numTracks));
    }
    out << (b ? "," : "") << "{\"name\":" << jsonString(body.name) << ",\"layer\":" << jsonString(body.layer)
        << ",\"visible\":" << (body.visible ? "true" : "false") << ",\"track\":" << body.track
        << ",\"pose\":" << poseJson(body.X_WB, what + " pose") << ",\"shapes\":[";
    for (std::size_t s = 0; s < body.shapes.size(); ++s) {
      out << (s ? "," : "") << shapeJson(body.shapes[s], what + " shape " + std::to_string(s));
    }
    out << "],\"pieces\":" << piecesJson(body.pieces, what) << "}";
  }
  out << "]";
}

/// A frame's contact as the page's arrays hold it: "1"/"0" in `has`, the distance (NaN when
/// absent) and pointA, pointB, normal; checked finite when present.
struct ContactArrays {
  std::string has;
  std::vector<double> distances;
  std::vector<float> points;

  void append(bool present, const ViewContact& c, const std::string& what) {
    has += present ? '1' : '0';
    if (present) {
      requireFinite(c.pointA, what + " point A");
      requireFinite(c.pointB, what + " point B");
      requireFinite(c.normal, what + " normal");
    }
    distances.push_back(present ? c.distance : std::nan(""));
    for (const Eigen::Vector3d* v : {&c.pointA, &c.pointB, &c.normal}) {
      for (int i = 0; i < 3; ++i) points.push_back(static_cast<float>((*v)[i]));
    }
  }
  /// The JSON fields has, distance, points.
  std::string json() const {
    return "\"has\":\"" + has + "\",\"distance\":" + base64Of(distances) + ",\"points\":" + base64Of(points);
  }
};

void writeFrames(const ViewScene& scene, std::ostream& out) {
  const std::size_t n = scene.frames.size();
  if (n == 0) throw std::invalid_argument("writeHtmlView: the scene has no frame");
  std::vector<float> poses;
  std::vector<double> values;
  ContactArrays contacts;      // the closest pair's
  ContactArrays bodyContacts;  // the body-level one
  std::string waypoints;
  std::string labels = "[";
  std::string names = "[";
  for (std::size_t f = 0; f < n; ++f) {
    const ViewFrame& frame = scene.frames[f];
    const std::string what = "frame " + std::to_string(f);
    if (static_cast<int>(frame.poses.size()) != scene.numTracks ||
        (!frame.hidden.empty() && frame.hidden.size() != frame.poses.size())) {
      throw std::invalid_argument("writeHtmlView: " + what + " has " + std::to_string(frame.poses.size()) +
                                  " track poses, the scene has " + std::to_string(scene.numTracks) + " tracks");
    }
    for (std::size_t t = 0; t < frame.poses.size(); ++t) {
      appendPose(frame.poses[t], what + " track " + std::to_string(t), poses);
      if (!frame.hidden.empty() && frame.hidden[t]) poses[poses.size() - 7] = std::nanf("");
    }
    values.push_back(frame.value);
    waypoints += frame.waypoint ? '1' : '0';
    labels += (f ? "," : "") + jsonString(frame.label);
    const ViewContact& c = frame.contact;
    contacts.append(frame.hasContact, c, what + " contact");
    names += (f ? "," : "") + jsonString(frame.hasContact ? c.nameA : "") + "," +
             jsonString(frame.hasContact ? c.nameB : "");
    bodyContacts.append(frame.hasBodyContact, frame.bodyContact, what + " body contact");
  }
  out << "\"frames\":{\"count\":" << n << ",\"tracks\":" << scene.numTracks << ",\"poses\":" << base64Of(poses)
      << ",\"waypoint\":\"" << waypoints << "\",\"value\":" << base64Of(values) << ",\"labels\":" << labels
      << "],\"contact\":{" << contacts.json() << ",\"names\":" << names << "]},\"bodyContact\":{" << bodyContacts.json()
      << "}}";
}

/// The template with every "@DEEPCHECK_<NAME>@" replaced by its text, scanned once (inserted text
/// is never searched for markers).
std::string expand(const std::string& page, const std::vector<std::pair<std::string, const char*>>& texts) {
  std::string out;
  std::size_t pos = 0;
  for (std::size_t at; (at = page.find("@DEEPCHECK_", pos)) != std::string::npos;) {
    const std::size_t end = page.find('@', at + 1);
    const std::string marker = page.substr(at, end == std::string::npos ? std::string::npos : end + 1 - at);
    const char* text = nullptr;
    for (const auto& [name, t] : texts) {
      if (name == marker) text = t;
    }
    if (!text) throw std::logic_error("viewer page template: unknown marker " + marker);
    out.append(page, pos, at - pos);
    out += text;
    pos = at + marker.size();
  }
  out.append(page, pos, std::string::npos);
  return out;
}

}  // namespace

void writeHtmlView(const ViewScene& scene, std::ostream& out) {
  std::ostringstream data;
  data << "{\"title\":" << jsonString(scene.title) << ",\"caption\":" << jsonString(scene.caption)
       << ",\"valueName\":" << jsonString(scene.valueName) << ",";
  writeBodies(scene, data);
  data << ",";
  writeFrames(scene, data);
  data << "}";
  const std::string json = data.str();
  const std::string page = expand(assets::kPage, {{"@DEEPCHECK_DATA@", json.c_str()},
                                                  {"@DEEPCHECK_VIEWER_JS@", assets::kViewerJs},
                                                  {"@DEEPCHECK_ORBIT_CONTROLS_JS@", assets::kOrbitControlsJs},
                                                  {"@DEEPCHECK_THREE_JS@", assets::kThreeJs},
                                                  {"@DEEPCHECK_VIEWER_CSS@", assets::kViewerCss}});
  out << page;
}

void writeHtmlView(const ViewScene& scene, const std::string& file) {
  std::ostringstream page;
  writeHtmlView(scene, page);
  std::ofstream out(file, std::ios::binary);
  if (!out) throw std::invalid_argument("writeHtmlView: cannot write '" + file + "'");
  out << page.str();
  out.close();
  if (!out) throw std::invalid_argument("writeHtmlView: error while writing '" + file + "'");
}

}  // namespace deepcheck::viewer
