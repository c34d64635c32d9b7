#include "mbs-run/constrained/consistent_start.h"

#include <algorithm>
#include <sstream>
#include <string>

#include "mbs-run/integrators/integrator.h"
#include "mbs-run/mechanics/flexible/flexible_body.h"

namespace fc::mbs {

void requireSatisfiable(System& sys, double t, const Eigen::VectorXd& y, double atol) {
  const System::Violations v = sys.violations(t, y);
  const double limit = std::max(1e-6, 100.0 * atol);
  if (!(v.position > limit)) return;
  std::ostringstream s;
  s << "unsatisfiable constraints at t = " << t << ": after projection the joints still miss by " << v.position
    << " (m or rad, limit " << limit << "), largest at joint "
    << (v.worst_joint >= 0 ? sys.model().joints[v.worst_joint].name : std::string("?"))
    << "; the joints contradict each other (check their points and axes)";
  throw UnsatisfiableConstraints(s.str());
}

namespace {

// The active joint of `body` (any when body < 0) whose points are farthest
// apart as placed, among the joints that make two points coincide; joint -1
// when there is none.
struct PlacedGap {
  int joint = -1;
  double gap = 0.0;  // [m]
};
PlacedGap largestPlacedGap(System& sys, const Eigen::VectorXd& placed, int body) {
  PlacedGap g;
  const Model& m = sys.model();
  for (std::size_t j = 0; j < m.joints.size(); ++j) {
    const Joint& jt = m.joints[j];
    if (!sys.jointRuntime(int(j)).enabled || (body >= 0 && jt.body_i != body && jt.body_j != body)) continue;
    const Eigen::VectorXd d = sys.jointPointGap(int(j), 0.0, placed);
    if (d.size() == 3 && d.norm() > g.gap) g = {int(j), d.norm()};
  }
  return g;
}

// A start whose joints the frames could not close and the modes did, by a
// deflection linear modes do not describe: the scene placed a body away
// from its joints where its other joints hold its frame (a body clamped as
// placed, its far end 0.5 m from its support). A deformation the joints
// need within that range (a 1 mm misfit, a preload) is kept.
void refuseDeformingStart(System& sys, const Eigen::VectorXd& placed, const Eigen::VectorXd& y) {
  const Model& m = sys.model();
  for (std::size_t k = 0; k < m.bodies.size(); ++k) {
    const Body& b = m.bodies[k];
    if (b.fixed || b.modes == 0) continue;
    const Eigen::VectorXd dq = y.segment(b.pos_index + 7, b.modes) - placed.segment(b.pos_index + 7, b.modes);
    const double limit = kAssemblyDeflection * flexibleBodySize(*b.flex, b.mass, b.inertia_com, b.com);
    for (const FlexInterface& it : b.flex->interfaces) {
      if (it.shapes.rows() != b.modes) continue;
      const auto [u, th] = interfaceMotion(it, dq);
      if (u <= limit && th <= kAssemblyDeflection) continue;
      const PlacedGap g = largestPlacedGap(sys, placed, int(k));
      std::ostringstream s;
      s << "unsatisfiable constraints at t = 0: body " << b.name << " is not placed assembled: ";
      if (g.joint >= 0)
        s << "joint " << m.joints[g.joint].name << "'s points are " << g.gap << " m apart at t = 0, ";
      s << "its frame cannot close them (its other joints hold it), and its modes would have to deflect interface "
        << it.name << " by " << u << " m and turn it by " << th << " rad (linear modes describe up to "
        << kAssemblyDeflection << " of the body's size, " << limit << " m, and " << kAssemblyDeflection
        << " rad); place the body where its joints hold, or give that deformation as its modal_coordinates";
      throw UnsatisfiableConstraints(s.str());
    }
  }
}

// The assembly ran out of passes while it was still closing the gap (it
// never reached a point where the joints pull against each other, which is
// requireSatisfiable's contradicting joints): say where the scene starts.
void refuseUnconvergedStart(System& sys, const Eigen::VectorXd& placed, const Eigen::VectorXd& y,
                            const System::Assembly& a, double limit) {
  const System::Violations v = sys.violations(0.0, y);
  if (!(v.position > limit) || a.stalled) return;
  const Model& m = sys.model();
  const PlacedGap g = largestPlacedGap(sys, placed, -1);
  std::ostringstream s;
  s << "unsatisfiable constraints at t = 0: the bodies are not placed assembled and the assembly did not "
       "close the gap in "
    << a.passes << " passes (still " << v.position << " m or rad at joint "
    << (v.worst_joint >= 0 ? m.joints[v.worst_joint].name : std::string("?")) << ")";
  if (g.joint >= 0) s << "; as placed, joint " << m.joints[g.joint].name << "'s points are " << g.gap << " m apart";
  s << ": place the bodies nearer where their joints hold";
  throw UnsatisfiableConstraints(s.str());
}

}  // namespace

Eigen::VectorXd consistentStart(System& sys, double atol) {
  Eigen::VectorXd y = sys.initialState();
  if (const std::string cause = sys.nonFiniteCause(0.0, y); !cause.empty())
    throw NonFiniteState("non-finite state: " + cause + " is not finite at t = 0 s");
  const Eigen::VectorXd placed = y;
  sys.initializeJoints(y);
  const System::Assembly a = sys.assemble(0.0, y);
  sys.initializeJoints(y);
  refuseDeformingStart(sys, placed, y);
  refuseUnconvergedStart(sys, placed, y, a, std::max(1e-6, 100.0 * atol));
  requireSatisfiable(sys, 0.0, y, atol);
  return y;
}

}  // namespace fc::mbs
