#include "mbs-run/scene/scene.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>

#include "common/rotations.h"
#include "mbs-run/monitors/bounding_volume_tree.h"
#include "mbs-run/run/margins.h"
#include "mbs-run/mechanics/flexible/flexible_body.h"
#include "mbs-run/mechanics/force_elements.h"
#include "mbs-run/mechanics/rigid_body.h"
#include "mbs-run/monitors/stress_recovery.h"
#include "mbs-run/run/run_policy.h"

namespace fc::mbs {

using Eigen::Vector3d;

namespace {

// Scene vectors in SI units, bounded: beyond these magnitudes a value is a unit
// mistake, and its squares and products overflow the dynamics. The fuzzer's
// 1e300 N force made every reaction infinite (refused only when the results
// were written, an error naming no key); a body placed 1e9 m from its joints
// integrated for ever behind 1e20 N reactions.
constexpr double kMaxLength = 1e6;  // m (1000 km: beyond any mechanism's scene)
constexpr double kMaxLoad = 1e12;   // N, N m
constexpr double kMaxSpeed = 1e6;   // m/s, rad/s
constexpr double kMaxGravity = 1e6; // m/s^2 (1e5 g, beyond any centrifuge)
// Spring-dampers: 1e15 N/m is a 1 m^2 steel bar 0.2 mm long, 1e12 N s/m
// (N m s/rad) damps such a spring on a tonne critically; beyond them a value
// is a unit mistake, and 1.7e308 made the run stop with a non-finite state
// instead of an input error.
constexpr double kMaxStiffness = 1e15;
constexpr double kMaxDamping = 1e12;

Vector3d vec3(const InputNode& n, double limit, const char* unit) {
  const Vector3d v = n.asVector(3);
  if (v.cwiseAbs().maxCoeff() > limit)  // the limits are powers of ten: "1e12"
    n.fail("expected components within 1e" + std::to_string(std::lround(std::log10(limit))) + " " + unit +
           " (SI units; beyond that is a unit mistake)");
  return v;
}

// Body and joint names become HDF5 group names in the results (/bodies/NAME,
// /joints/NAME): refuse the ones HDF5 would read as a path, here at their key.
std::string groupName(const InputNode& n) { return n.asName(); }

Vector3d unitVector(const InputNode& n) {
  const Vector3d v = n.asVector(3);
  if (v.norm() < 1e-12) n.fail("expected a non-zero direction vector, got [0, 0, 0]");
  return v.normalized();
}

Eigen::Matrix3d inertiaMatrix(const InputNode& n) {
  const Eigen::Matrix3d I = n.asMatrix(3, 3);
  if ((I - I.transpose()).cwiseAbs().maxCoeff() > 1e-9 * (1.0 + I.cwiseAbs().maxCoeff()))
    n.fail("expected a symmetric 3x3 inertia tensor");
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(I);
  const Eigen::Vector3d ev = es.eigenvalues();
  if (ev.minCoeff() <= 0.0)
    n.fail("expected a positive definite inertia tensor (principal moments > 0)");
  // Triangle inequality of principal moments (any real mass distribution).
  if (ev[0] + ev[1] < ev[2] * (1 - 1e-9))
    n.fail("principal moments violate I1 + I2 >= I3: not a physical mass distribution");
  return I;
}

// A body given as a rigid block, or as a uniform rod or plate from dimensions.
void parseInertia(const InputNode& b, Body& body) {
  int given = b.has("rigid") + b.has("rod") + b.has("plate") + b.has("flexible");
  if (given != 1)
    b.fail("expected exactly one of 'rigid', 'rod', 'plate' or 'flexible' to define the body's inertia");
  if (b.has("flexible")) {
    // Reduced flexible body from an fe-prep body file (errors at the key).
    auto flex = std::make_shared<FlexibleBodyData>(loadFlexibleBody(b["flexible"]));
    const InertiaInvariants& inv = flex->inertia;
    body.mass = inv.mass;
    body.com = inv.centerOfMass();
    const Eigen::Matrix3d cs = fc::skew(body.com);
    body.inertia_com = inv.inertiaAboutOrigin() + body.mass * cs * cs;  // back to the CoM
    body.modes = flex->modes;
    body.flex = flex;
    return;
  }
  if (b.has("rigid")) {
    const InputNode r = b["rigid"];
    r.allowKeys({"mass", "center_of_mass", "inertia"});
    body.mass = r["mass"].asPositive();
    body.com = r.has("center_of_mass") ? vec3(r["center_of_mass"], kMaxLength, "m") : Vector3d::Zero();
    body.inertia_com = inertiaMatrix(r["inertia"]);
    return;
  }
  // Uniform solids: the mass from `mass`, or from `density` and the volume.
  auto massOf = [](const InputNode& n, double volume) {
    if (n.has("mass") == n.has("density"))
      n.fail("expected exactly one of 'mass' or 'density'");
    return n.has("mass") ? n["mass"].asPositive() : n["density"].asPositive() * volume;
  };
  if (b.has("rod")) {
    const InputNode r = b["rod"];
    r.allowKeys({"length", "diameter", "mass", "density"});
    const double L = r["length"].asPositive(), d = r["diameter"].asPositive();
    body.mass = massOf(r, L * 0.25 * M_PI * d * d);
    body.inertia_com = rodInertia(body.mass, L, d);
  } else {
    const InputNode p = b["plate"];
    p.allowKeys({"length", "width", "thickness", "mass", "density"});
    const double a = p["length"].asPositive(), w = p["width"].asPositive(), t = p["thickness"].asPositive();
    body.mass = massOf(p, a * w * t);
    body.inertia_com = plateInertia(body.mass, a, w, t);
  }
  body.com.setZero();
}

// Initial modal coordinates and rates (kg^1/2 m, per mass-normalised mode)
// are hard to judge by eye: bound what they do at the body's interfaces. A
// deflection beyond 10 times the body's size or a turn beyond 10 rad is far
// outside linear modes and a unit mistake (1e9 on a pinned-pinned beam turned
// its ends by 1e10 rad and ran for minutes at 1e-7 s steps, fuzz campaign); a
// rate beyond kMaxSpeed as for any body.
void checkInitialModalState(const Body& body, const InputNode& b) {
  const FlexibleBodyData& f = *body.flex;
  const Eigen::VectorXd& q = body.modal_coordinates;
  const Eigen::VectorXd& qd = body.modal_velocities;
  const double size = flexibleBodySize(f, body.mass, body.inertia_com, body.com);
  for (const FlexInterface& it : f.interfaces) {
    if (it.shapes.rows() != q.size()) continue;
    const auto [u, th] = interfaceMotion(it, q);
    if (!(u <= 10.0 * size) || !(th <= 10.0)) {
      std::ostringstream os;
      os << "these modal coordinates deflect interface " << it.name << " by " << u << " m and turn it by " << th
         << " rad (limits: 10 times the body's size, " << 10.0 * size
         << " m, and 10 rad): linear modes describe small deflections; check the units (kg^1/2 m per "
            "mass-normalised mode)";
      b["modal_coordinates"].fail(os.str());
    }
    const double v = interfaceMotion(it, qd).displacement;
    if (!(v <= kMaxSpeed)) {
      std::ostringstream os;
      os << "these modal rates move interface " << it.name << " at " << v << " m/s, beyond " << kMaxSpeed << " m/s";
      b["modal_velocities"].fail(os.str());
    }
  }
}

Body parseBody(const InputNode& b) {
  b.allowKeys({"name", "rigid", "rod", "plate", "flexible", "fixed", "position", "orientation", "velocity",
               "angular_velocity", "modal_coordinates", "modal_velocities", "geometry"});
  Body body;
  body.name = groupName(b["name"]);
  parseInertia(b, body);
  if (b.has("rod")) body.geometry = std::make_shared<BodyGeometry>(rodGeometry(b["rod"]["length"].asPositive()));
  if (b.has("plate"))
    body.geometry = std::make_shared<BodyGeometry>(
        rectangleGeometry(b["plate"]["length"].asPositive(), b["plate"]["width"].asPositive()));
  if (b.has("geometry")) {
    const InputNode g = b["geometry"];
    if (body.flex) g.fail("a flexible body's geometry is its mesh in the body file");
    g.allowKeys({"segment", "rectangle"});
    if (g.has("segment") == g.has("rectangle")) g.fail("expected one of 'segment' or 'rectangle'");
    auto geo = std::make_shared<BodyGeometry>();
    if (g.has("segment")) {
      const InputNode sgm = g["segment"];
      if (!sgm.isSequence() || sgm.size() != 2) sgm.fail("expected two end points [[x, y, z], [x, y, z]] (body frame)");
      geo->vertices.resize(3, 2);
      geo->vertices.col(0) = vec3(sgm.at(0), kMaxLength, "m");
      geo->vertices.col(1) = vec3(sgm.at(1), kMaxLength, "m");
      geo->segments.push_back({0, 1});
    } else {
      const Eigen::VectorXd lw = g["rectangle"].asVector(2);
      if (!(lw.minCoeff() > 0)) g["rectangle"].fail("expected [length, width] > 0 (body x and y, centred)");
      *geo = rectangleGeometry(lw[0], lw[1]);
    }
    body.geometry = geo;
  }
  body.fixed = b.flag("fixed", false);
  if (body.fixed && body.flex) b["fixed"].fail("a flexible body cannot be fixed: use a rigid body, or clamp it with a fixed joint");
  if (b.has("position")) body.position = vec3(b["position"], kMaxLength, "m");
  if (b.has("orientation")) {
    const Eigen::VectorXd p = b["orientation"].asVector(4);
    const double n = p.norm();
    if (std::abs(n - 1.0) > 1e-6)
      b["orientation"].fail("expected unit Euler parameters [e0, e1, e2, e3], got norm " + std::to_string(n));
    body.orientation = Eigen::Vector4d(p / n);
  }
  if (b.has("velocity")) body.velocity = vec3(b["velocity"], kMaxSpeed, "m/s");
  if (b.has("angular_velocity")) body.angular_velocity = vec3(b["angular_velocity"], kMaxSpeed, "rad/s");
  if (body.fixed && (body.velocity.norm() > 0 || body.angular_velocity.norm() > 0))
    b.fail("a fixed body cannot have an initial velocity");
  // One value per mode used (`modes:` of the flexible entry), in the file's order; zero if absent.
  auto initialModal = [&](const char* key, Eigen::VectorXd& out) {
    out = Eigen::VectorXd::Zero(body.modes);
    if (!b.has(key)) return;
    if (!body.flex) b[key].fail("only a flexible body has modal coordinates");
    out = b[key].asVector(body.modes);
  };
  initialModal("modal_coordinates", body.modal_coordinates);
  initialModal("modal_velocities", body.modal_velocities);
  if (body.flex) checkInitialModalState(body, b);
  return body;
}

int bodyRef(const Model& m, const InputNode& n) {
  const std::string name = n.asString();
  const int k = m.bodyIndex(name);
  if (k < 0) {
    std::vector<std::string> names;
    for (const Body& b : m.bodies) names.push_back(b.name);
    n.fail("unknown body '" + name + "'" + didYouMean(name, names));
  }
  return k;
}

// A joint or force point: body-frame coordinates (moving with the frame only),
// or, on a flexible body, the name of one of its interfaces (moving with the
// modes too).
Vector3d pointRef(const Model& m, int body, const InputNode& n, PointShapes& shapes) {
  const Body& b = m.bodies[body];
  shapes.psi = Eigen::MatrixXd::Zero(3, b.modes);
  shapes.theta = Eigen::MatrixXd::Zero(3, b.modes);
  if (n.isScalar()) {
    const std::string name = n.asString();
    if (!b.flex)
      n.fail("'" + name + "' names an interface, but body '" + b.name +
             "' is rigid: expected body-frame coordinates [x, y, z]");
    if (!b.flex->findInterface(name)) {
      const std::vector<std::string> names = b.flex->interfaceNames();
      std::string known;
      for (const auto& k : names) known += (known.empty() ? "" : ", ") + k;
      n.fail("body '" + b.name + "' (" + b.flex->file + ") has no interface '" + name + "'" +
             didYouMean(name, names) + "; it has: " + known);
    }
    const Marker mk = b.flex->marker(name);
    shapes.psi = mk.Psi;
    shapes.theta = mk.Theta;
    return mk.s0;
  }
  return vec3(n, kMaxLength, "m");
}

JointType jointType(const InputNode& n) {
  const std::string t = n.asString();
  if (t == "spherical") return JointType::Spherical;
  if (t == "revolute") return JointType::Revolute;
  if (t == "fixed") return JointType::Fixed;
  if (t == "universal") return JointType::Universal;
  if (t == "cylindrical") return JointType::Cylindrical;
  if (t == "prismatic") return JointType::Prismatic;
  n.fail("unknown joint type '" + t + "': expected spherical, revolute, fixed, universal, cylindrical or prismatic" +
         didYouMean(t, {"spherical", "revolute", "fixed", "universal", "cylindrical", "prismatic"}));
}

Joint parseJoint(const Model& m, const InputNode& j) {
  j.allowKeys({"name", "type", "bodies", "points", "axes", "initial_angle", "enabled", "locked", "drive", "limits",
               "stop_only"});
  Joint jt;
  jt.name = groupName(j["name"]);
  jt.type = jointType(j["type"]);
  const InputNode bodies = j["bodies"];
  if (!bodies.isSequence() || bodies.size() != 2) bodies.fail("expected two body names [first, second]");
  jt.body_i = bodyRef(m, bodies.at(0));
  jt.body_j = bodyRef(m, bodies.at(1));
  if (jt.body_i == jt.body_j) bodies.fail("expected two different bodies");
  if (m.bodies[jt.body_i].fixed && m.bodies[jt.body_j].fixed)
    bodies.fail("both bodies are fixed: the joint would constrain nothing");
  const InputNode pts = j["points"];
  if (!pts.isSequence() || pts.size() != 2) pts.fail("expected two points [on first body, on second body]");
  jt.point_i = pointRef(m, jt.body_i, pts.at(0), jt.shapes_i);
  jt.point_j = pointRef(m, jt.body_j, pts.at(1), jt.shapes_j);
  if (pts.at(0).isScalar()) jt.interface_i = pts.at(0).asString();
  if (pts.at(1).isScalar()) jt.interface_j = pts.at(1).asString();
  const bool needs_axes = jt.type == JointType::Revolute || jt.type == JointType::Universal ||
                          jt.type == JointType::Cylindrical || jt.type == JointType::Prismatic;
  if (needs_axes) {
    const InputNode ax = j["axes"];
    if (!ax.isSequence() || ax.size() != 2) ax.fail("expected two axes [on first body, on second body]");
    jt.axis_i = unitVector(ax.at(0));
    jt.axis_j = unitVector(ax.at(1));
  } else if (j.has("axes")) {
    j["axes"].fail("a " + j["type"].asString() + " joint has no axes");
  }
  jt.enabled = j.flag("enabled", true);
  if (j.has("locked") && jt.type != JointType::Revolute) j["locked"].fail("only revolute joints can be locked");
  jt.locked = j.flag("locked", false);
  if (j.has("initial_angle")) {
    if (jt.type != JointType::Revolute) j["initial_angle"].fail("only revolute joints have an angle");
    jt.initial_angle = j["initial_angle"].asDouble();
  }
  if (j.has("drive")) {
    const InputNode d = j["drive"];
    if (jt.type != JointType::Revolute) d.fail("only revolute joints can be driven");
    if (jt.locked) d.fail("a driven joint cannot also be locked");
    d.allowKeys({"angle0", "speed", "amplitude", "frequency", "phase", "spin_up"});
    jt.drive.active = true;
    jt.drive.angle0 = d.number("angle0", jt.initial_angle);
    jt.drive.speed = d.number("speed", 0.0);
    jt.drive.amplitude = d.number("amplitude", 0.0);
    jt.drive.frequency = d.number("frequency", 0.0);
    jt.drive.phase = d.number("phase", 0.0);
    if (d.has("spin_up")) {
      const InputNode su = d["spin_up"];
      su.allowKeys({"rate", "time"});
      jt.drive.spin_rate = su["rate"].asDouble();
      jt.drive.spin_time = su["time"].asDouble();
      if (!(jt.drive.spin_time > 0)) su["time"].fail("expected a spin-up time > 0 [s]");
    }
    if (!j.has("initial_angle")) jt.initial_angle = jt.drive.angle(0.0);
  }
  if (j.has("limits")) {
    const InputNode l = j["limits"];
    if (jt.type != JointType::Revolute) l.fail("only revolute joints have limits (stops on the angle)");
    if (jt.drive.active) l.fail("a driven joint cannot have limits: its angle is prescribed");
    l.allowKeys({"min", "max", "restitution"});
    JointLimits& lim = jt.limits;
    lim.has_min = l.has("min");
    lim.has_max = l.has("max");
    if (!lim.any()) l.fail("expected 'min', 'max' or both [rad]");
    if (lim.has_min) lim.min = l["min"].asDouble();
    if (lim.has_max) lim.max = l["max"].asDouble();
    if (lim.has_min && lim.has_max && !(lim.max > lim.min))
      l["max"].fail("expected max > min, got min " + std::to_string(lim.min) + ", max " + std::to_string(lim.max));
    lim.restitution = l.has("restitution") ? l["restitution"].asNonNegative() : 0.0;
    if (lim.restitution > 1.0) l["restitution"].fail("expected a restitution coefficient in [0, 1]");
    // The start must be inside the stops (a rounding of the given angle aside).
    const double slack = 1e-9 * (1.0 + std::abs(jt.initial_angle));
    if ((lim.has_min && jt.initial_angle < lim.min - slack) || (lim.has_max && jt.initial_angle > lim.max + slack))
      l.fail("the initial angle " + std::to_string(jt.initial_angle) + " rad is outside the limits");
  }
  if (j.has("stop_only")) {
    if (jt.type != JointType::Revolute) j["stop_only"].fail("only a revolute joint can be stop_only");
    jt.stop_only = j["stop_only"].asBool();
    if (jt.stop_only && jt.drive.active) j["stop_only"].fail("a stop_only joint cannot be driven");
  }
  return jt;
}

PiecewiseLinear parseTable(const InputNode& t) {
  t.allowKeys({"angle", "value"});
  PiecewiseLinear f;
  const Eigen::VectorXd a = t["angle"].asVector(), v = t["value"].asVector();
  if (a.size() != v.size())
    t.fail("expected 'angle' and 'value' of the same length, got " + std::to_string(a.size()) + " and " +
           std::to_string(v.size()));
  if (a.size() < 1) t["angle"].fail("expected at least one point");
  for (Eigen::Index k = 1; k < a.size(); ++k)
    if (!(a[k] > a[k - 1])) t["angle"].fail("expected strictly increasing angles");
  f.x.assign(a.data(), a.data() + a.size());
  f.y.assign(v.data(), v.data() + v.size());
  return f;
}

// A flexible body's whole file (mesh, mode shapes), for the scene keys that
// name its mesh nodes (a contact's edge, the contact monitor); a file that
// cannot be read is an error at the key `at`.
fc::FlexBodyFile readBodyMesh(const Body& b, const InputNode& at) {
  try {
    return fc::readFlexBody(b.flex->file, b.modes, fc::FlexBodyParts::All);
  } catch (const std::bad_alloc&) {
    throw;  // out of memory is no input error
  } catch (const std::exception& e) {
    at.fail(std::string("cannot read the mesh of body '") + b.name + "': " + e.what());
  }
}

// Mesh node k of a body file as one of a contact's points: its position and
// its translation and rotation mode shapes (the first `modes` columns).
void pushMeshNode(const fc::FlexBodyFile& f, Eigen::Index k, int modes, ForceElement& fe) {
  fe.edge_points.push_back(f.body.nodes.row(k).transpose());
  PointShapes sh;
  sh.psi = f.body.shapes.block(6 * k, 0, 3, modes);
  sh.theta = f.body.shapes.block(6 * k + 3, 0, 3, modes);
  fe.edge_shapes.push_back(sh);
}

// A contact's edge on `body`: `points:` (interface names or body
// coordinates, in order along the edge), or `from:`/`to:` on a flexible
// body: the mesh nodes within `tolerance` of that line (body coordinates),
// ordered along it, each moving with its node's mode shapes.
void parseEdge(const Model& m, int body, const InputNode& e, ForceElement& fe) {
  e.allowKeys({"points", "from", "to", "tolerance", "half_thickness"});
  const Body& b = m.bodies[body];
  fe.edge_half_thickness = e.has("half_thickness") ? e["half_thickness"].asNonNegative() : 0.0;
  if (e.has("points") == (e.has("from") || e.has("to")))
    e.fail("expected either 'points' (the edge's points in order) or 'from' and 'to' (a line of the body's mesh nodes)");
  if (e.has("points")) {
    const InputNode pts = e["points"];
    if (!pts.isSequence() || pts.size() < 2) pts.fail("expected at least two points along the edge");
    for (std::size_t k = 0; k < pts.size(); ++k) {
      PointShapes sh;
      fe.edge_points.push_back(pointRef(m, body, pts.at(k), sh));
      fe.edge_shapes.push_back(sh);
    }
    return;
  }
  if (!b.flex) e.fail("'from'/'to' select mesh nodes, but body '" + b.name + "' is rigid: give 'points'");
  const Vector3d from = vec3(e["from"], kMaxLength, "m"), to = vec3(e["to"], kMaxLength, "m");
  const double tol = e.has("tolerance") ? e["tolerance"].asNonNegative() : 1e-4;
  const Vector3d dir = to - from;
  if (!(dir.norm() > 0.0)) e["to"].fail("expected 'to' apart from 'from'");
  const fc::FlexBodyFile f = readBodyMesh(b, e);
  std::vector<std::pair<double, Eigen::Index>> on;  // (position along the line, node)
  for (Eigen::Index k = 0; k < f.body.nodes.rows(); ++k) {
    const Vector3d x = f.body.nodes.row(k).transpose();
    const double t = (x - from).dot(dir) / dir.squaredNorm();
    if (t < -1e-9 || t > 1.0 + 1e-9) continue;
    if ((x - from - t * dir).norm() <= tol) on.push_back({t, k});
  }
  std::sort(on.begin(), on.end());
  if (on.size() < 2)
    e.fail("found " + std::to_string(on.size()) + " mesh node(s) of body '" + b.name + "' within " +
           std::to_string(tol) + " m of the line from 'from' to 'to': expected at least two (check the body "
           "coordinates, or widen 'tolerance')");
  for (const auto& [t, k] : on) pushMeshNode(f, k, b.modes, fe);
}

// A contact's surface on a flexible `body`: its mesh's shell triangles (those
// with a node within `near: {from, to, distance}` of that line, body
// coordinates, when given: a fine mesh's triangles far from where the contact
// can act cost time at every evaluation), each node moving with its mode
// shapes; `half_thickness` the shell's half thickness about the mid-surface.
void parseSurface(const Model& m, int body, const InputNode& sf, ForceElement& fe) {
  sf.allowKeys({"half_thickness", "near"});
  const Body& b = m.bodies[body];
  if (!b.flex) sf.fail("a surface is a flexible body's shell mesh, but body '" + b.name + "' is rigid");
  fe.edge_half_thickness = sf.has("half_thickness") ? sf["half_thickness"].asNonNegative() : 0.0;
  const fc::FlexBodyFile f = readBodyMesh(b, sf);
  const Eigen::Index n = f.body.nodes.rows();
  std::vector<char> close(n, 1);
  if (sf.has("near")) {
    const InputNode nr = sf["near"];
    nr.allowKeys({"from", "to", "distance"});
    const Vector3d from = vec3(nr["from"], kMaxLength, "m"), to = vec3(nr["to"], kMaxLength, "m");
    const double dist = nr["distance"].asNonNegative();
    for (Eigen::Index k = 0; k < n; ++k) {
      double s = 0.0, t = 0.0;
      const Vector3d x = f.body.nodes.row(k).transpose();
      closestSegmentPoints(x, x, from, to, s, t);
      close[k] = (x - (from + t * (to - from))).norm() <= dist;
    }
  }
  std::vector<int> index(n, -1);  // mesh node -> the contact's node
  for (const auto& [kind, el] : f.body.elements) {
    if (el.cols() != 3) continue;
    for (Eigen::Index e = 0; e < el.rows(); ++e) {
      if (!close[el(e, 0)] && !close[el(e, 1)] && !close[el(e, 2)]) continue;
      std::array<int, 3> t{};
      for (int c = 0; c < 3; ++c) {
        const Eigen::Index k = el(e, c);
        if (index[k] < 0) {
          index[k] = int(fe.edge_points.size());
          pushMeshNode(f, k, b.modes, fe);
        }
        t[c] = index[k];
      }
      fe.surface_triangles.push_back(t);
    }
  }
  if (fe.surface_triangles.empty())
    sf.fail("body '" + b.name + "' has no shell triangles" + (sf.has("near") ? " near that line" : " in its file"));
}

// The plane of a contact on body j: {point, normal} with an optional
// rectangle patch {axis, half_sizes}.
void parsePlane(const Model& m, const InputNode& pl, ForceElement& fe) {
  pl.allowKeys({"point", "normal", "rectangle"});
  fe.point_j = pointRef(m, fe.body_j, pl["point"], fe.shapes_j);
  if (pl["point"].isScalar()) fe.interface_j = pl["point"].asString();
  fe.vector = unitVector(pl["normal"]);
  if (pl.has("rectangle")) {
    const InputNode r = pl["rectangle"];
    r.allowKeys({"axis", "half_sizes"});
    const Vector3d u = unitVector(r["axis"]);
    const Vector3d u_in = u - u.dot(fe.vector) * fe.vector;
    if (!(u_in.norm() > 1e-6)) r["axis"].fail("expected an axis in the plane (not along its normal)");
    fe.patch_axis = u_in.normalized();
    const Eigen::VectorXd h = r["half_sizes"].asVector(2);
    if (!(h[0] > 0.0 && h[1] > 0.0)) r["half_sizes"].fail("expected two half sizes > 0 [m]");
    fe.patch_half_u = h[0];
    fe.patch_half_v = h[1];
  }
}

// `type: contact`: a point of the first body against a plane of the second,
// a segment of the first against an edge of the second, or an edge of the
// first against a plane of the second (force_elements.h, contactState).
void parseContact(const Model& m, const InputNode& f, ForceElement& fe) {
  f.allowKeys({"name", "type", "bodies", "point", "plane", "segment", "edge", "surface", "stiffness", "exponent",
               "restitution", "impact_speed", "radius", "enabled"});
  fe.type = ForceType::Contact;
  const InputNode b = f["bodies"];
  if (!b.isSequence() || b.size() != 2)
    b.fail("expected two body names [body of the point, segment or edge; body of the plane or edge]");
  fe.body_i = bodyRef(m, b.at(0));
  fe.body_j = bodyRef(m, b.at(1));
  if (fe.body_i == fe.body_j) b.fail("expected two different bodies");
  const int firsts = int(f.has("point")) + int(f.has("segment")) + int(f.has("edge") && !f.has("segment"));
  if (firsts != 1)
    f.fail("expected one of: 'point' and 'plane' (point against plane), 'segment' and 'edge' (segment against "
           "edge), 'segment' and 'surface' (segment against a flexible body's shell triangles), 'edge' and 'plane' "
           "(edge against plane)");
  if (f.has("surface") && !f.has("segment")) f["surface"].fail("a 'surface' is met by a 'segment' of the first body");
  if (f.has("segment")) {
    fe.contact_kind = ForceElement::ContactKind::SegmentEdge;
    if (f.has("plane")) f["plane"].fail("a segment acts against an 'edge' or a 'surface', not a plane");
    if (f.has("surface") && f.has("edge")) f["surface"].fail("expected either 'edge' or 'surface', not both");
    if (f.has("radius")) f["radius"].fail("a segment's radius is segment: {radius}");
    const InputNode sg = f["segment"];
    sg.allowKeys({"points", "radius"});
    const InputNode pts = sg["points"];
    if (!pts.isSequence() || pts.size() != 2) pts.fail("expected the segment's two end points");
    fe.point_i = pointRef(m, fe.body_i, pts.at(0), fe.shapes_i);
    fe.point_i2 = pointRef(m, fe.body_i, pts.at(1), fe.shapes_i2);
    if ((fe.point_i2 - fe.point_i).norm() == 0.0) pts.fail("expected two distinct end points");
    fe.segment_radius = sg.has("radius") ? sg["radius"].asNonNegative() : 0.0;
    if (f.has("surface")) {
      fe.contact_kind = ForceElement::ContactKind::SegmentSurface;
      parseSurface(m, fe.body_j, f["surface"], fe);
    } else {
      parseEdge(m, fe.body_j, f["edge"], fe);
    }
  } else if (f.has("edge")) {
    fe.contact_kind = ForceElement::ContactKind::EdgePlane;
    parseEdge(m, fe.body_i, f["edge"], fe);
    parsePlane(m, f["plane"], fe);
  } else {
    fe.point_i = pointRef(m, fe.body_i, f["point"], fe.shapes_i);
    if (f["point"].isScalar()) fe.interface_i = f["point"].asString();
    parsePlane(m, f["plane"], fe);
  }
  fe.exponent = f.has("exponent") ? f["exponent"].asInRange(1.0, 3.0, "") : 1.0;
  if (fe.exponent != 1.0 && f.units())
    f["exponent"].fail("a contact stiffness with an exponent other than 1 is in N/m^exponent, which units: cannot "
                       "convert: give this scene in SI (no units:) or use exponent 1");
  fe.stiffness = f["stiffness"].asInRange(0.0, kMaxStiffness, "N/m^exponent");
  if (!(fe.stiffness > 0.0)) f["stiffness"].fail("expected a contact stiffness > 0");
  if (f.has("restitution") != f.has("impact_speed"))
    f.fail("expected 'restitution' and 'impact_speed' together (the restitution e is met at impacts of speed v0)");
  if (f.has("restitution")) {
    const double e = f["restitution"].asNonNegative();
    if (!(e > 0.0 && e <= 1.0)) f["restitution"].fail("expected a restitution coefficient in (0, 1]");
    const double v0 = f["impact_speed"].asNonNegative();
    if (!(v0 > 0.0)) f["impact_speed"].fail("expected an impact speed > 0 [m/s]");
    fe.hysteresis = 3.0 * (1.0 - e * e) / (4.0 * v0);
  }
  fe.radius = f.has("radius") ? f["radius"].asNonNegative() : 0.0;
}

ForceElement parseForce(const Model& m, const InputNode& f, int index) {
  const std::string type = f["type"].asString();
  ForceElement fe;
  fe.name = f.has("name") ? f["name"].asName() : type + "#" + std::to_string(index);
  fe.enabled = f.flag("enabled", true);
  if (type == "gravity") {
    f.allowKeys({"name", "type", "g", "enabled"});
    fe.type = ForceType::Gravity;
    fe.vector = vec3(f["g"], kMaxGravity, "m/s^2");
  } else if (type == "rotational_spring_damper") {
    f.allowKeys({"name", "type", "joint", "damping", "torque", "enabled"});
    fe.type = ForceType::RotationalSpringDamper;
    const InputNode jn = f["joint"];
    fe.joint = m.jointIndex(jn.asString());
    if (fe.joint < 0) jn.fail("unknown joint '" + jn.asString() + "'");
    if (m.joints[fe.joint].type != JointType::Revolute)
      jn.fail("expected a revolute joint, '" + jn.asString() + "' is not one");
    fe.damping = f.has("damping") ? f["damping"].asInRange(0.0, kMaxDamping, "N m s/rad") : 0.0;
    if (f.has("torque")) fe.torque = parseTable(f["torque"]);
  } else if (type == "translational_spring_damper") {
    f.allowKeys({"name", "type", "bodies", "points", "stiffness", "damping", "free_length", "enabled"});
    fe.type = ForceType::TranslationalSpringDamper;
    const InputNode b = f["bodies"];
    if (!b.isSequence() || b.size() != 2) b.fail("expected two body names");
    fe.body_i = bodyRef(m, b.at(0));
    fe.body_j = bodyRef(m, b.at(1));
    const InputNode p = f["points"];
    if (!p.isSequence() || p.size() != 2) p.fail("expected two points");
    fe.point_i = pointRef(m, fe.body_i, p.at(0), fe.shapes_i);
    fe.point_j = pointRef(m, fe.body_j, p.at(1), fe.shapes_j);
    if (p.at(0).isScalar()) fe.interface_i = p.at(0).asString();
    if (p.at(1).isScalar()) fe.interface_j = p.at(1).asString();
    fe.stiffness = f["stiffness"].asInRange(0.0, kMaxStiffness, "N/m");
    fe.damping = f.has("damping") ? f["damping"].asInRange(0.0, kMaxDamping, "N s/m") : 0.0;
    fe.free_length = f["free_length"].asNonNegative();
  } else if (type == "contact") {
    parseContact(m, f, fe);
  } else if (type == "force") {
    f.allowKeys({"name", "type", "body", "point", "force", "enabled"});
    fe.type = ForceType::ConstantForce;
    fe.body_i = bodyRef(m, f["body"]);
    fe.point_i = f.has("point") ? pointRef(m, fe.body_i, f["point"], fe.shapes_i) : m.bodies[fe.body_i].com;
    if (f.has("point") && f["point"].isScalar()) fe.interface_i = f["point"].asString();
    if (!f.has("point")) {
      fe.shapes_i.psi = Eigen::MatrixXd::Zero(3, m.bodies[fe.body_i].modes);
      fe.shapes_i.theta = Eigen::MatrixXd::Zero(3, m.bodies[fe.body_i].modes);
    }
    fe.vector = vec3(f["force"], kMaxLoad, "N");
  } else if (type == "torque") {
    f.allowKeys({"name", "type", "body", "torque", "enabled"});
    fe.type = ForceType::ConstantTorque;
    fe.body_i = bodyRef(m, f["body"]);
    fe.vector = vec3(f["torque"], kMaxLoad, "N m");
  } else {
    f["type"].fail("unknown force type '" + type +
                   "': expected gravity, rotational_spring_damper, translational_spring_damper, contact, force or "
                   "torque" +
                   didYouMean(type, {"gravity", "rotational_spring_damper", "translational_spring_damper", "contact",
                                     "force", "torque"}));
  }
  return fe;
}

Event parseEvent(const Model& m, const InputNode& e) {
  e.allowKeys({"time", "joint", "angle", "direction", "lock", "release", "enable", "disable"});
  Event ev;
  if (e.has("time") == e.has("joint"))
    e.fail("expected either 'time' or 'joint' with 'angle' (a joint-angle crossing)");
  if (e.has("time")) {
    ev.time = e["time"].asNonNegative();
  } else {
    const InputNode jn = e["joint"];
    ev.joint = m.jointIndex(jn.asString());
    if (ev.joint < 0) jn.fail("unknown joint '" + jn.asString() + "'");
    if (m.joints[ev.joint].type != JointType::Revolute) jn.fail("expected a revolute joint");
    ev.angle = e["angle"].asDouble();
    const std::string dir = e.string("direction", "any");
    if (dir == "rising") ev.direction = 1;
    else if (dir == "falling") ev.direction = -1;
    else if (dir == "any") ev.direction = 0;
    else e["direction"].fail("expected rising, falling or any, got '" + dir + "'");
  }
  auto names = [&](const char* key) {
    std::vector<std::pair<std::string, InputNode>> out;
    if (!e.has(key)) return out;
    const InputNode l = e[key];
    if (!l.isSequence()) l.fail("expected a list of names");
    for (std::size_t k = 0; k < l.size(); ++k) out.emplace_back(l.at(k).asString(), l.at(k));
    return out;
  };
  for (const auto& [name, node] : names("lock")) {
    const int j = m.jointIndex(name);
    if (j < 0 || m.joints[j].type != JointType::Revolute) node.fail("expected the name of a revolute joint, got '" + name + "'");
    ev.lock.push_back(j);
  }
  for (const auto& [name, node] : names("release")) {
    const int j = m.jointIndex(name);
    if (j < 0 || m.joints[j].type != JointType::Revolute) node.fail("expected the name of a revolute joint, got '" + name + "'");
    ev.release.push_back(j);
  }
  for (const char* key : {"enable", "disable"}) {
    const bool on = std::string(key) == "enable";
    for (const auto& [name, node] : names(key)) {
      const int j = m.jointIndex(name), f = m.forceIndex(name);
      if (j >= 0) (on ? ev.enable_joints : ev.disable_joints).push_back(j);
      else if (f >= 0) (on ? ev.enable_forces : ev.disable_forces).push_back(f);
      else node.fail("expected the name of a joint or force element, got '" + name + "'");
    }
  }
  return ev;
}

// Named speed/accuracy presets, chosen from the measured study on the flexible
// SAR antenna (docs/accuracy.md): a preset only fills in defaults, so any key
// written next to it in the scene wins.
struct Preset {
  const char* name;
  double rtol;
  IntegratorKind integrator;
};
// `fast` lets auto hand stiff segments to TR-BDF2 (its order-2 error is
// inside what rtol 1e-4 asks); `accurate` keeps fifth order throughout.
constexpr Preset kPresets[] = {
    {"fast", 1e-4, IntegratorKind::Auto},
    {"accurate", 1e-7, IntegratorKind::DormandPrince},
};

void applyPreset(const InputNode& node, Settings& st) {
  const std::string name = node.asString();
  std::vector<std::string> known;
  for (const Preset& p : kPresets) {
    if (name == p.name) {
      st.rtol = p.rtol;
      st.integrator = p.integrator;
      return;
    }
    known.push_back(p.name);
  }
  node.fail("unknown preset '" + name + "'" + didYouMean(name, known) +
            "; expected fast or accurate");
}

// "a, b or c".
std::string oneOf(const std::vector<std::string>& names) {
  std::string s;
  for (std::size_t k = 0; k < names.size(); ++k)
    s += (k == 0 ? "" : k + 1 == names.size() ? " or " : ", ") + names[k];
  return s;
}

void parseSimulation(const InputNode& s, Settings& st) {
  s.allowKeys({"preset", "t_end", "output_step", "rtol", "atol", "integrator", "max_step", "penalty",
               "stabilization_frequency", "stabilization_damping", "multiplier_iterations", "linear_solver",
               "formulation"});
  if (auto fm = s.get("formulation")) {
    const std::string v = fm->asString();
    if (v == "auto") st.formulation = Formulation::Auto;
    else if (v == "tree") st.formulation = Formulation::Tree;
    else if (v == "constrained") st.formulation = Formulation::Constrained;
    else fm->fail("expected auto, tree or constrained, got '" + v + "'");
  }
  if (auto ls = s.get("linear_solver")) {
    const std::string v = ls->asString();
    if (v == "auto") st.linear_solver = AlMethod::Automatic;
    else if (v == "schur") st.linear_solver = AlMethod::BlockSchur;
    else if (v == "sparse_schur") st.linear_solver = AlMethod::SparseSchur;
    else if (v == "sparse") st.linear_solver = AlMethod::SparseLdlt;
    else ls->fail("expected auto, schur, sparse_schur or sparse, got '" + v + "'");
  }
  if (s.has("preset")) applyPreset(s["preset"], st);
  st.t_end = s["t_end"].asPositive();
  st.output_step = s.has("output_step") ? s["output_step"].asPositive() : st.t_end / 100.0;
  if (s.has("rtol")) {
    st.rtol = s["rtol"].asPositive();
    if (st.rtol >= 0.1 || st.rtol < 1e-13) s["rtol"].fail("expected 1e-13 <= rtol < 0.1");
  }
  if (s.has("atol")) st.atol = s["atol"].asPositive();
  if (s.has("max_step")) st.max_step = s["max_step"].asPositive();
  if (s.has("penalty")) st.penalty = s["penalty"].asPositive();
  if (s.has("stabilization_frequency")) st.omega = s["stabilization_frequency"].asNonNegative();
  if (s.has("stabilization_damping")) st.xi = s["stabilization_damping"].asNonNegative();
  if (s.has("multiplier_iterations")) {
    const long k = s["multiplier_iterations"].asInt();
    if (k < 1 || k > 100) s["multiplier_iterations"].fail("expected 1 to 100, got " + std::to_string(k));
    st.multiplier_iterations = static_cast<int>(k);
  }
  if (!s.has("integrator")) return;  // keep the preset's (or the default auto)
  const std::string integ = s["integrator"].asString();
  if (const std::optional<IntegratorKind> kind = integratorNamed(integ)) st.integrator = *kind;
  else s["integrator"].fail("expected " + oneOf(integratorNames()) + ", got '" + integ + "'");
}

template <class F>
void forEachEntry(const InputNode& root, const char* key, F&& f) {
  // `joints:` written empty is an empty list (has() refuses other valueless keys).
  if (root.isMap() && root.raw()[key] && root.raw()[key].IsNull()) return;
  if (!root.has(key)) return;
  const InputNode list = root[key];
  if (!list.isSequence()) list.fail(std::string("expected a list of ") + key);
  for (std::size_t k = 0; k < list.size(); ++k) f(list.at(k), static_cast<int>(k));
}


// A flexible body's geometry for the contact monitor: its mesh (shell
// triangles, beam elements as segments) with each node's modal displacement.
std::shared_ptr<BodyGeometry> meshGeometry(const Body& b, const InputNode& at) {
  const fc::FlexBodyFile f = readBodyMesh(b, at);
  auto g = std::make_shared<BodyGeometry>();
  const Eigen::Index n = f.body.nodes.rows();
  g->vertices = f.body.nodes.transpose();
  g->modal_displacement.resize(3 * n, b.modes);
  for (Eigen::Index k = 0; k < n; ++k)
    g->modal_displacement.middleRows(3 * k, 3) = f.body.shapes.block(6 * k, 0, 3, b.modes);
  for (const auto& [kind, el] : f.body.elements) {
    for (Eigen::Index e = 0; e < el.rows(); ++e) {
      if (el.cols() == 3) g->triangles.push_back({int(el(e, 0)), int(el(e, 1)), int(el(e, 2))});
      else if (el.cols() == 2) g->segments.push_back({int(el(e, 0)), int(el(e, 1))});
    }
  }
  if (g->triangles.empty() && g->segments.empty()) at.fail("body '" + b.name + "' has no mesh elements in its file");
  return g;
}

// outputs.stresses: flexible bodies whose stresses are recovered at every
// output (stress_recovery.h); their files' recovery data is read here, the
// other bodies' never.
void parseStresses(const InputNode& list, Model& m) {
  if (!list.isSequence()) list.fail("expected a list of flexible body names, e.g. [panel2, panel3]");
  for (std::size_t k = 0; k < list.size(); ++k) {
    const InputNode n = list.at(k);
    Body& b = m.bodies[bodyRef(m, n)];
    if (!b.flex)
      n.fail("body '" + b.name + "' is not flexible: stress recovery needs a flexible body (flexible: {file: ...}) "
             "written by fe-prep");
    if (b.stress) n.fail("body '" + b.name + "' is named twice");
    try {
      b.stress = loadStressRecovery(b.flex->file, b.modes);
    } catch (const std::bad_alloc&) {
      throw;  // out of memory is no input error
    } catch (const std::exception& e) {
      n.fail("cannot recover the stresses of body '" + b.name + "': " + e.what());
    }
  }
}

int jointRef(const Model& m, const InputNode& n) {
  const std::string name = n.asString();
  const int k = m.jointIndex(name);
  if (k < 0) {
    std::vector<std::string> names;
    for (const Joint& j : m.joints) names.push_back(j.name);
    n.fail("unknown joint '" + name + "'" + didYouMean(name, names));
  }
  return k;
}

// outputs.margins (run/margins.h, docs/mbs-run.md "Margins"):
//   beams: [{body: B11, EI: 10.12, ends: pinned, joints: [S5, S2]}, ...]
//   joints: [R1, H23, ...]   (printed in the summary; every joint's peaks are written)
void parseMargins(const InputNode& mg, Model& m) {
  mg.allowKeys({"beams", "joints"});
  if (mg.has("beams")) {
    const InputNode list = mg["beams"];
    if (!list.isSequence()) list.fail("expected a list of {body: NAME, EI: N m^2, ends: pinned, joints: [A, B]}");
    for (std::size_t k = 0; k < list.size(); ++k) {
      const InputNode b = list.at(k);
      b.allowKeys({"body", "EI", "ends", "joints", "length"});
      BeamMarginSpec spec;
      spec.body = bodyRef(m, b["body"]);
      const std::string& name = m.bodies[static_cast<std::size_t>(spec.body)].name;
      spec.EI = b["EI"].asDouble();
      if (!(spec.EI > 0)) b["EI"].fail("expected the bending stiffness EI of the weaker axis in N m^2 (> 0)");
      spec.ends = b.has("ends") ? b["ends"].asString() : "pinned";
      spec.K = effectiveLengthFactor(spec.ends);
      if (spec.K <= 0) b["ends"].fail("expected pinned, fixed, fixed_pinned or fixed_free, got '" + spec.ends + "'");
      std::vector<int> on;  // joints attached to the body
      if (b.has("joints")) {
        const InputNode jl = b["joints"];
        if (!jl.isSequence() || jl.size() != 2) jl.fail("expected the two joints at the member's ends, [A, B]");
        for (std::size_t i = 0; i < 2; ++i) {
          const int j = jointRef(m, jl.at(i));
          const Joint& jt = m.joints[static_cast<std::size_t>(j)];
          if (jt.body_i != spec.body && jt.body_j != spec.body)
            jl.at(i).fail("joint '" + jt.name + "' does not connect body '" + name + "'");
          on.push_back(j);
        }
        if (on[0] == on[1]) jl.fail("expected two different joints");
      } else {
        for (std::size_t j = 0; j < m.joints.size(); ++j)
          if (m.joints[j].body_i == spec.body || m.joints[j].body_j == spec.body) on.push_back(static_cast<int>(j));
        if (on.size() != 2)
          b["body"].fail("body '" + name + "' has " + std::to_string(on.size()) +
                         " joints: name the two at its ends with `joints: [A, B]`");
      }
      spec.joint_a = on[0];
      spec.joint_b = on[1];
      const Joint& ja = m.joints[static_cast<std::size_t>(on[0])];
      const Joint& jb = m.joints[static_cast<std::size_t>(on[1])];
      const Eigen::Vector3d pa = ja.body_i == spec.body ? ja.point_i : ja.point_j;
      const Eigen::Vector3d pb = jb.body_i == spec.body ? jb.point_i : jb.point_j;
      spec.length = b.has("length") ? b["length"].asDouble() : (pb - pa).norm();
      if (!(spec.length > 0)) b.fail("the member's length is 0: give `length:` in m");
      spec.euler_load = eulerLoad(spec.EI, spec.length, spec.K);
      for (const BeamMarginSpec& o : m.margin_beams)
        if (o.body == spec.body) b["body"].fail("body '" + name + "' is named twice");
      m.margin_beams.push_back(spec);
    }
  }
  if (mg.has("joints")) {
    const InputNode jl = mg["joints"];
    if (!jl.isSequence()) jl.fail("expected a list of joint names");
    for (std::size_t k = 0; k < jl.size(); ++k) m.margin_joints.push_back(jointRef(m, jl.at(k)));
  }
}

void parseOutputs(const InputNode& o, Model& m) {
  o.allowKeys({"distances", "stresses", "stress_every", "margins"});
  if (o.has("margins")) parseMargins(o["margins"], m);
  if (o.has("stresses")) parseStresses(o["stresses"], m);
  if (o.has("stress_every")) {
    // Decimates the full stress fields only (docs/stresses.md); the bound keeps
    // a typo (an output count, a time in ms) from silently leaving one row.
    const InputNode k = o["stress_every"];
    const long every = k.asInt();
    if (every < 1 || every > 1000000) k.fail("expected a whole number of output rows from 1 to 1000000, got " + std::to_string(every));
    if (!o.has("stresses")) k.fail("stress_every decimates the fields of outputs.stresses, which is not given");
    m.stress_every = static_cast<int>(every);
  }
  if (!o.has("distances")) return;
  const InputNode d = o["distances"];
  if (!d.isSequence()) d.fail("expected a list of body pairs [[A, B], ...]");
  for (std::size_t k = 0; k < d.size(); ++k) {
    const InputNode p = d.at(k);
    if (!p.isSequence() || p.size() != 2) p.fail("expected a pair of body names [A, B]");
    std::array<int, 2> pair{bodyRef(m, p.at(0)), bodyRef(m, p.at(1))};
    if (pair[0] == pair[1]) p.fail("expected two different bodies");
    // Each pair is one results group /distances/A-B: a repeat was refused only
    // when the file was written ("cannot create /distances/h2-d", no key named).
    for (const auto& q : m.distance_pairs)
      if ((q[0] == pair[0] && q[1] == pair[1]) || (q[0] == pair[1] && q[1] == pair[0]))
        p.fail("the pair " + m.bodies[pair[0]].name + "-" + m.bodies[pair[1]].name + " is listed twice");
    for (int i = 0; i < 2; ++i) {
      Body& b = m.bodies[pair[i]];
      if (!b.geometry && b.flex) b.geometry = meshGeometry(b, p.at(i));
      if (!b.geometry)
        p.at(i).fail("body '" + b.name + "' has no geometry: give it `geometry: {segment: [[x, y, z], [x, y, z]]}` or "
                     "`geometry: {rectangle: [length, width]}` (rod and plate bodies and flexible bodies have one)");
      if (!b.geometry_tree) b.geometry_tree = std::make_shared<BoundingTree>(buildBoundingTree(*b.geometry));
    }
    m.distance_pairs.push_back(pair);
  }
}

}  // namespace

Model parseScene(const InputNode& root) {
  root.allowKeys({"units", "bodies", "joints", "forces", "events", "simulation", "materials", "laminates", "outputs"});
  Model m;
  m.source = root.file();
  std::set<std::string> names;
  forEachEntry(root, "bodies", [&](const InputNode& b, int) {
    Body body = parseBody(b);
    if (!names.insert(body.name).second) b["name"].fail("duplicate name '" + body.name + "'");
    m.bodies.push_back(body);
  });
  if (m.bodies.empty()) root.fail("expected at least one body under 'bodies'");
  m.finalize();
  if (m.nv == 0) root["bodies"].fail("every body is fixed: nothing to simulate");
  forEachEntry(root, "joints", [&](const InputNode& j, int) {
    Joint jt = parseJoint(m, j);
    if (!names.insert(jt.name).second) j["name"].fail("duplicate name '" + jt.name + "'");
    m.joints.push_back(jt);
  });
  forEachEntry(root, "forces", [&](const InputNode& f, int k) {
    ForceElement fe = parseForce(m, f, k);
    if (f.has("name") && !names.insert(fe.name).second) f["name"].fail("duplicate name '" + fe.name + "'");
    m.forces.push_back(fe);
  });
  forEachEntry(root, "events", [&](const InputNode& e, int) { m.events.push_back(parseEvent(m, e)); });
  if (root.has("outputs")) parseOutputs(root["outputs"], m);
  parseSimulation(root["simulation"], m.settings);
  return m;
}

Model loadScene(const std::string& path) { return parseScene(InputNode::loadFile(path)); }

}  // namespace fc::mbs
