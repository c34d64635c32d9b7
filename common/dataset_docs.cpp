#include "common/dataset_docs.h"

#include <sstream>

namespace fc {

namespace {

std::vector<std::string> split(const std::string& path) {
  std::vector<std::string> parts;
  std::stringstream ss(path);
  std::string p;
  while (std::getline(ss, p, '/'))
    if (!p.empty()) parts.push_back(p);
  return parts;
}

bool matches(const std::string& pattern, const std::string& path) {
  const auto a = split(pattern), b = split(path);
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (a[i] != "*" && a[i] != b[i]) return false;
  return true;
}

}  // namespace

// A table, one row per dataset, kept whole so that it reads as the list it is
// (allowed its length in tests/docs/function_length.py).
const std::vector<DatasetDoc>& datasetDocs() {
  static const std::vector<DatasetDoc> docs = {
      // section-prep
      {"section", "/stiffness/timoshenko", "N, N m, N m^2 (by entry)",
       "6x6 Timoshenko stiffness about the section origin, order [extension, shear x2, shear x3, "
       "torsion, bending about x2, bending about x3] (VABS order)"},
      {"section", "/stiffness/classical", "N, N m, N m^2 (by entry)",
       "4x4 classical stiffness about the section origin, order [extension, torsion, bending about "
       "x2, bending about x3]"},
      {"section", "/mass/matrix", "kg/m, kg, kg m (by entry)",
       "6x6 mass matrix per unit length about the section origin, Timoshenko order"},
      {"section", "/mass/per_length", "kg/m", "mass per unit length"},
      {"section", "/centers/mass", "m", "mass centre (x2, x3)"},
      {"section", "/centers/tension", "m", "tension centre (x2, x3): where an axial force causes no bending"},
      {"section", "/centers/shear", "m", "shear centre (x2, x3): where a transverse force causes no twist"},
      {"section", "/centers/geometric", "m", "area centroid (x2, x3)"},
      {"section", "/section/area", "m^2", "cross-section area"},
      {"section", "/section/elements", "1", "number of 2-D elements of the section mesh"},
      {"section", "/section/nodes", "1", "number of nodes of the section mesh"},
      {"section", "/recovery/stress", "Pa per N or N m",
       "(6, n_elements, 6): stress at each section element's centroid per unit Timoshenko resultant "
       "[F1, F2, F3, M1, M2, M3], components [s11, s22, s33, s23, s13, s12] in the section frame"},
      {"section", "/recovery/strain", "1 per N or N m",
       "(6, n_elements, 6): strain per unit resultant, [e11, e22, e33, g23, g13, g12] (engineering "
       "shear) in the section frame"},
      {"section", "/recovery/ply_stress", "Pa per N or N m",
       "(6, n_elements, 3): [s_11, s_22, t_12] in each element's material axes per unit resultant "
       "(isotropic elements: 1 = beam axis)"},
      {"section", "/recovery/ply_strain", "1 per N or N m",
       "(6, n_elements, 3): [e_11, e_22, g_12] in each element's material axes per unit resultant"},
      {"section", "/recovery/material_axes", "1",
       "(n_elements, 3, 3): rows y1 (fibre), y2, y3 (ply normal) of each element in section components"},
      {"section", "/mesh/centroids", "m", "(n_elements, 2): section element centroids (x2, x3)"},
      {"section", "/mesh/material", "1", "(n_elements): each section element's material name"},
      {"section", "/mesh/material_index", "1", "(n_elements): index of each element's material in /materials/names"},
      {"section", "/mesh/has_plies", "1",
       "(n_elements): 1 where the material is not isotropic (a ply with a fibre), 0 where recovery "
       "uses the section frame with the beam axis as 1-axis"},
      {"section", "/materials/names", "1", "(n_materials): the section's material names"},
      {"section", "/materials/strength", "Pa",
       "(n_materials, 5): Xt Xc Yt Yc S12 of each material; 0 where the material has no strengths"},
      {"section", "/recovered/resultants", "N, N m", "[F1, F2, F3, M1, M2, M3] of section-prep --recover"},
      {"section", "/recovered/stress", "Pa", "(n_elements, 6): stresses for /recovered/resultants, section frame"},
      {"section", "/recovered/strain", "1", "(n_elements, 6): strains for /recovered/resultants, section frame"},
      {"section", "/recovered/ply_stress", "Pa", "(n_elements, 3): [s_11, s_22, t_12], material axes"},
      {"section", "/recovered/ply_strain", "1", "(n_elements, 3): [e_11, e_22, g_12], material axes"},
      {"section", "/recovered/failure_index", "1", "(n_elements): Tsai-Wu index (contracts.md formula); 0 without strengths"},
      {"section", "/recovered/max_stress_index", "1", "(n_elements): maximum-stress index; 0 without strengths"},
      {"section", "/recovered/strength_ratio", "1",
       "(n_elements): load factor at which the Tsai-Wu index reaches 1; 0 without strengths, 1e300 if never"},
      {"section", "/recovered/hashin", "1",
       "(n_elements, 4): Hashin's 3D indices, fibre tension, fibre compression, matrix tension, matrix compression "
       "(docs/stresses.md); 0 for the mode the stress's sign does not select and without strengths"},
      // fe-prep
      {"flexbody", "/mesh/nodes", "m", "undeformed node positions in the body frame (n_nodes, 3)"},
      {"flexbody", "/mesh/triangles", "1", "shell triangles, 0-based node indices (n, 3)"},
      {"flexbody", "/mesh/beams", "1", "beam elements, 0-based node indices (n, 2)"},
      {"flexbody", "/modes/frequencies_hz", "Hz", "natural frequencies of the constrained modes"},
      {"flexbody", "/modes/eigenvalues", "rad^2/s^2", "omega^2 of each mode"},
      {"flexbody", "/modes/shapes", "kg^-1/2 (translations), rad kg^-1/2 m^-1 (rotations)",
       "mass-normalised mode shapes (n_modes, n_nodes, 6): u1 u2 u3 theta1 theta2 theta3 per node"},
      {"flexbody", "/view/*", "kg^-1/2, rad kg^-1/2 m^-1 (modes); kg (nodal_mass)",
       "views for ParaView (BODY.xdmf), virtual datasets holding no data of their own: mode_NN and "
       "mode_NN_rotation are /modes/shapes[NN-1, :, 0:3] and [NN-1, :, 3:6], nodal_mass is /mass/nodal[:, 0]"},
      {"flexbody", "/mass/nodal", "kg, kg m^2",
       "lumped mass and the three rotary inertias (body axes) of each node (n_nodes, 4)"},
      {"flexbody", "/inertia/mass", "kg", "mass of the simulated body (what its invariants imply)"},
      {"flexbody", "/inertia/center_of_mass", "m", "centre of mass of the simulated body, body frame, undeformed"},
      {"flexbody", "/inertia/tensor", "kg m^2",
       "inertia tensor of the simulated body about the body origin, body axes, undeformed"},
      {"flexbody", "/inertia/exact/mass", "kg", "exact continuum mass, where it differs from /inertia/mass"},
      {"flexbody", "/inertia/exact/center_of_mass", "m", "exact continuum centre of mass, where it differs"},
      {"flexbody", "/inertia/exact/tensor", "kg m^2", "exact continuum inertia tensor about the body origin, where it differs"},
      {"flexbody", "/interfaces/*/node", "1", "index of the node the interface is rigidly attached to (distributed: the patch node nearest the point)"},
      {"flexbody", "/interfaces/*/position", "m", "interface position, body frame, undeformed"},
      {"flexbody", "/interfaces/*/shapes", "kg^-1/2 (translations), rad kg^-1/2 m^-1 (rotations)",
       "the interface point's own displacement and rotation per mode (n_modes, 6)"},
      {"flexbody", "/regions/*/members", "1",
       "a general body's region: 0-based rows of /mesh/triangles, /mesh/beams or /mesh/nodes (attribute members_of); attributes name, kind (shell, beam, set, masses), property, element, axis, summary"},
      {"flexbody", "/regions/*/mass", "kg", "the region's mass (shell: laminate and non-structural mass per area times area; beam: mass per length times length)"},
      {"flexbody", "/regions/*/axes", "1",
       "(n_members, 3) unit vectors, body frame: each triangle's fibre (0 deg) reference axis, each beam's section x2"},
      {"flexbody", "/interfaces/*/static_compliance", "m/N, rad/(N m)",
       "exact static deflection of the point under a unit force x y z / moment x y z (6; reference-held bodies, or with inertia relief when static_error or static_correction asks)"},
      {"flexbody", "/interfaces/*/static_participation", "1",
       "each mode's share of that static deflection (n_modes, 6)"},
      {"flexbody", "/interfaces/*/static_error", "1",
       "share of that static deflection the file's modes miss (6; 0 where the point is held)"},
      {"flexbody", "/mesh/centroids", "m",
       "element centroids (shells) or midpoints (beams), body frame, undeformed (n_elements, 3)"},
      {"flexbody", "/stress/strains", "1 and 1/m per kg^1/2 m",
       "shells: membrane strains eps_xx eps_yy gamma_xy and curvatures kappa_xx kappa_yy kappa_xy at each element "
       "centroid per unit modal coordinate, laminate axes (n_modes, n_elements, 6)"},
      {"flexbody", "/stress/section/ply_stress", "Pa per N or N m",
       "(6, n_section_elements, 3): the beam section's ply stresses [s_11, s_22, t_12] per unit resultant "
       "[N, V2, V3, T, M2, M3] (section-prep's /recovery/ply_stress)"},
      {"flexbody", "/stress/section/centroids", "m", "(n_section_elements, 2): section element centroids (x2, x3)"},
      {"flexbody", "/stress/section/material", "1", "(n_section_elements): material name of each section element"},
      {"flexbody", "/stress/section/has_plies", "1", "(n_section_elements): 1 for a ply material, 0 isotropic"},
      {"flexbody", "/stress/section/strength", "Pa", "(n_section_elements, 5): Xt Xc Yt Yc S12, zero where none"},
      {"flexbody", "/stress/beam_lengths", "m", "(n_elements): length of each beam element"},
      {"flexbody", "/stress/stations", "m",
       "(3 n_elements, 3): each beam element's first node, midpoint and second node, body frame"},
      {"results", "/bodies/*/stations", "m",
       "(n_stations, 3): body-frame points on a beam's axis where its section stresses are recovered"},
      {"flexbody", "/stress/section_resultants", "N and N m per kg^1/2 m",
       "beams: section resultants N V2 V3 T M2 M3 at each element midpoint per unit modal coordinate, element "
       "section axes (n_modes, n_elements, 6)"},
      {"flexbody", "/stress/plies/z_mid", "m", "shells: mid-thickness height of each ply from the mid-surface, bottom up (n_plies)"},
      {"flexbody", "/stress/plies/angle_deg", "deg", "shells: fibre angle of each ply from the laminate x axis (n_plies)"},
      {"flexbody", "/stress/plies/stiffness", "Pa",
       "shells: plane-stress reduced stiffness Q of each ply in its material axes, order [11, 22, 12] (n_plies, 3, 3)"},
      {"flexbody", "/stress/plies/strength", "Pa",
       "shells: Xt Xc Yt Yc S12 of each ply (n_plies, 5); only when every ply's material has a strength"},
      {"flexbody", "/invariants/*", "SI (see docs/body-file.md)",
       "inertia invariant of the floating-frame formulation, lumped-mass sums (docs/body-file.md)"},
      {"flexbody", "/geometric_stiffness/matrices", "1/m, 1",
       "modal geometric stiffness per unit inertial load case (12, n_modes, n_modes), cases in attribute `cases` "
       "(docs/body-file.md, Geometric stiffness)"},
      {"flexbody", "/geometric_stiffness/interfaces/*/matrices", "1/N, 1/(N m)",
       "modal geometric stiffness of a unit force x y z / moment x y z at the interface (6, n_modes, n_modes), "
       "interfaces the reference does not hold (docs/body-file.md, Geometric stiffness)"},
      // mbs-run
      {"results", "/time", "s", "output times"},
      {"results", "/bodies/*/position", "m", "body frame origin, global"},
      {"results", "/bodies/*/orientation", "1", "Euler parameters [e0, e1, e2, e3] of the body frame"},
      {"results", "/bodies/*/velocity", "m/s", "velocity of the body frame origin, global"},
      {"results", "/bodies/*/angular_velocity", "rad/s", "angular velocity of the body frame, global"},
      {"results", "/bodies/*/modal_coordinates", "kg^1/2 m", "modal coordinates of a flexible body"},
      {"results", "/bodies/*/modal_velocities", "kg^1/2 m/s", "modal velocities of a flexible body"},
      {"results", "/bodies/*/modal_energy", "J", "energy of each mode, 1/2 omega^2 q^2 + 1/2 qdot^2"},
      {"results", "/bodies/*/modal_energy_peak", "J", "each mode's largest modal_energy over the run"},
      {"results", "/bodies/*/ply_stress", "Pa",
       "outputs.stresses bodies: sigma_11 sigma_22 tau_12 of each ply in its material axes at its mid-thickness, "
       "at the element centroids (n_out, n_elements, n_plies, 3); with outputs.stress_every the rows of /stress_time"},
      {"results", "/bodies/*/failure_index", "1",
       "outputs.stresses bodies with ply strengths: Tsai-Wu index of each ply at each element centroid, failure at 1 "
       "(n_out, n_elements, n_plies); with outputs.stress_every the rows of /stress_time"},
      {"results", "/bodies/*/hashin", "1",
       "outputs.stresses bodies with ply strengths: Hashin's fibre tension, fibre compression, matrix tension and "
       "matrix compression indices of each ply (plane-stress form, docs/stresses.md), failure at 1 "
       "(n_out, n_elements or n_stations, n_plies or n_section_elements, 4); with outputs.stress_every the rows of /stress_time"},
      {"results", "/bodies/*/hashin_peak", "1",
       "the largest of each Hashin mode index over every output row (n_elements or n_stations, n_plies or n_section_elements, 4)"},
      {"results", "/margins/failure_index", "1, s, 1, 1",
       "(n_bodies_with_index, 4): each outputs.stresses body's peak Tsai-Wu index over the run, its time, element "
       "(beams: station) and ply (beams: section element), 0-based; attribute bodies lists the rows' bodies"},
      {"results", "/bodies/*/section_forces", "N, N m",
       "outputs.stresses beam bodies: section forces N V2 V3 T M2 M3 at each element midpoint, element section axes "
       "(n_out, n_elements, 6); with outputs.stress_every the rows of /stress_time"},
      {"results", "/stress_time", "s",
       "outputs.stress_every given: the output times of the rows the full stress fields hold (rows 0, K, 2K, ... "
       "and the last)"},
      {"results", "/bodies/*/failure_index_peak", "1",
       "outputs.stresses bodies with ply strengths: largest Tsai-Wu index of each ply over every output row "
       "(n_elements, n_plies)"},
      {"results", "/bodies/*/failure_index_peak_time", "s",
       "time of the first output row at which each element and ply reaches its failure_index_peak (n_elements, n_plies)"},
      {"results", "/bodies/*/ply_stress_at_peak", "Pa",
       "sigma_11 sigma_22 tau_12 of each ply in the row of its failure_index_peak (n_elements, n_plies, 3)"},
      {"results", "/bodies/*/ply_stress_max", "Pa",
       "outputs.stresses bodies without ply strengths: largest of each ply stress component over every output row "
       "(n_elements, n_plies, 3)"},
      {"results", "/bodies/*/ply_stress_min", "Pa",
       "the same, smallest (n_elements, n_plies, 3)"},
      {"results", "/bodies/*/section_forces_max", "N, N m",
       "outputs.stresses beam bodies and the beams of mixed shell+beam bodies: largest of each section force "
       "component over every output row (n_elements, 6)"},
      {"results", "/bodies/*/beam_ply_stress", "Pa",
       "mixed shell+beam bodies whose beam sections carry a recovery basis: the beams' ply_stress (n_out, n_stations, "
       "n_section_elements, 3), beside the shells' own"},
      {"results", "/bodies/*/beam_failure_index", "1",
       "the same bodies' beams: Tsai-Wu index (n_out, n_stations, n_section_elements)"},
      {"results", "/bodies/*/beam_hashin", "1",
       "the same bodies' beams: Hashin's four mode indices (n_out, n_stations, n_section_elements, 4)"},
      {"results", "/bodies/*/beam_failure_index_peak", "1",
       "the same bodies' beams: largest Tsai-Wu index over every output row (n_stations, n_section_elements)"},
      {"results", "/bodies/*/beam_failure_index_peak_time", "s",
       "time of the first output row reaching beam_failure_index_peak (n_stations, n_section_elements)"},
      {"results", "/bodies/*/beam_ply_stress_at_peak", "Pa",
       "the beams' ply stresses in the row of their beam_failure_index_peak (n_stations, n_section_elements, 3)"},
      {"results", "/bodies/*/beam_hashin_peak", "1",
       "the beams' largest Hashin mode indices over every output row (n_stations, n_section_elements, 4)"},
      {"results", "/bodies/*/section_forces_min", "N, N m",
       "the same, smallest (n_elements, 6)"},
      {"results", "/joints/*/angle", "rad",
       "revolute angle: rotation of the second body relative to the first about the axis, unwrapped"},
      {"results", "/joints/*/reaction_force", "N", "joint reaction force on the first body, global"},
      {"results", "/joints/*/reaction_torque", "N m", "joint reaction torque on the first body, global"},
      {"results", "/joints/*/limit_state", "1",
       "stop contact state: 0 free, -1 resting on the min stop, +1 on the max stop, 2 locked"},
      {"results", "/joints/*/limit_torque", "N m",
       "torque of the resting stop about the joint axis, positive driving the angle up; 0 when free"},
      {"results", "/joints/*/limit_impacts", "s, rad/s, rad/s, N m s, J",
       "one row per impact on a stop: time, angle rate before, after, angular impulse, energy dissipated"},
      {"results", "/distances/*", "m", "contact monitor: smallest distance between the two bodies' geometry"},
      {"results", "/energy/kinetic", "J", "kinetic energy of all bodies"},
      {"results", "/energy/potential", "J", "potential energy of gravity and springs"},
      {"results", "/energy/strain", "J", "elastic strain energy of flexible bodies"},
      {"results", "/energy/dissipated", "J", "energy dissipated by dampers and impacts since t = 0"},
      {"results", "/energy/applied_work", "J", "work of actuators and applied forces since t = 0"},
      {"results", "/diagnostics/constraint_violation", "m or rad",
       "largest position-level constraint violation"},
  };
  return docs;
}

const DatasetDoc* findDatasetDoc(const std::string& format, const std::string& path) {
  for (const auto& d : datasetDocs())
    if (d.format == format && matches(d.pattern, path)) return &d;
  return nullptr;
}

void annotateDatasets(H5File& f) {
  if (!f.hasAttribute("/", "format")) return;
  const std::string fmt = f.stringAttribute("/", "format");
  const std::string format = fmt.substr(0, fmt.find('/'));
  walkTree(f, "/", [&](const H5TreeEntry& e) {
    if (e.kind == H5TreeEntry::Kind::Group) return true;
    if (e.kind != H5TreeEntry::Kind::Dataset || e.seen_before) return false;
    if (const DatasetDoc* doc = findDatasetDoc(format, e.path)) {
      if (!f.hasAttribute(e.path, "units")) f.setAttribute(e.path, "units", doc->units);
      if (!f.hasAttribute(e.path, "description")) f.setAttribute(e.path, "description", doc->description);
    }
    return false;
  });
}

}  // namespace fc
