#pragma once
// The finite element mesh of one body, in the body frame: what the mesher
// produces, the assembly consumes and the body file stores under /mesh/.
// Besides the geometry it carries each element's properties: every triangle
// and beam names its property (an index into the body's shell or beam
// property table) and has its own material frame (the fibre reference axis
// projected on the triangle, the section x2 axis of the beam), so that one
// body may hold several laminates, shell kinds and beam sections.
#include <Eigen/Dense>
#include <array>
#include <map>
#include <string>
#include <vector>

#include "common/laminate.h"
#include "common/stress_data.h"
#include "fe-prep/elements/shell_triangle.h"

namespace fc::feprep {

// The section of a shell region: laminate (ABD, shear, mass; any non-structural
// mass per area already in mass_per_area), element kind and the plies for
// stress recovery.
struct ShellProperty {
  std::string name;           // the region (or Nastran PID<n>)
  std::string laminate_name;  // the laminate or material it was built from
  LaminateStiffness laminate;
  PlyTable plies;
  fe::ShellKind kind = fe::ShellKind::DST;
  double non_structural_mass = 0.0;  // kg/m^2, included in laminate.mass_per_area
};

// The section of a beam region (VABS order about the section origin on the axis).
struct BeamProperty {
  std::string name;
  std::string source;  // section file or inline shape
  Matrix6d Ks = Matrix6d::Zero();
  Matrix6d Ms = Matrix6d::Zero();
};

// A concentrated mass at a node: mass and inertia tensor about its own point
// `point` (body frame), rigidly attached to `node`.
struct PointMass {
  long node = -1;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  double mass = 0.0;
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
};

struct Mesh {
  Eigen::MatrixXd nodes;                       // (n_nodes, 3)
  std::vector<std::array<long, 3>> triangles;  // counter-clockwise about the normal
  std::vector<std::array<long, 2>> beams;
  // Named node sets usable in `reference:` (edges, beam ends, geo physical groups).
  std::map<std::string, std::vector<long>> sets;

  // Where each element came from: an index into `groups` (a physical group, a
  // Nastran property), -1 for none; used to give elements their properties.
  std::vector<std::string> groups;
  std::vector<int> triangle_group, beam_group;

  // Per-element properties (assigned after meshing, fe-prep/element_properties.h).
  std::vector<ShellProperty> shell_properties;
  std::vector<BeamProperty> beam_properties;
  std::vector<int> triangle_property;           // index into shell_properties
  std::vector<Eigen::Vector3d> triangle_axis;   // fibre reference axis (0 deg) of each triangle, body frame
  std::vector<int> beam_property;               // index into beam_properties
  std::vector<Eigen::Vector3d> beam_x2;         // each beam's section x2 direction (Nastran's v vector)
  std::vector<PointMass> point_masses;

  long nodeCount() const { return static_cast<long>(nodes.rows()); }
  // Index of the node closest to p, and its distance.
  long nearestNode(const Eigen::Vector3d& p, double* distance = nullptr) const;
  double characteristicLength() const;  // bounding-box diagonal

  const ShellProperty& shellProperty(long triangle) const {
    return shell_properties[static_cast<std::size_t>(triangle_property[static_cast<std::size_t>(triangle)])];
  }
  const BeamProperty& beamProperty(long beam) const {
    return beam_properties[static_cast<std::size_t>(beam_property[static_cast<std::size_t>(beam)])];
  }
};

}  // namespace fc::feprep
