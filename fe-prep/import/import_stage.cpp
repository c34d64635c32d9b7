#include "fe-prep/import/import_stage.h"

#include <cmath>
#include <cstdio>

#include "fe-prep/assembly.h"
#include "fe-prep/import/solid_faces.h"
#include "fe-prep/modal_solver.h"

namespace fc::feprep {

Eigen::VectorXd importedFreeEigenvalues(Comm comm, const ImportedModel& model, long count) {
  DofMap map = buildDofMap(model.mesh, {});
  holdSolidRotations(map, model.solid);
  const Eigen::MatrixXd rigid_full = admissibleRigidModes(model.mesh, {});
  Eigen::MatrixXd rigid(map.reduced, rigid_full.cols());
  for (long j = 0; j < rigid_full.cols(); ++j) rigid.col(j) = map.restrict(rigid_full.col(j));
  AssembledSystem sys;
  assemble(comm, model.pairs, map, model.pairCount(), [&](long e, ElementResult& out) { model.pairMatrices(e, out); }, sys);
  ModalRequest req;
  req.modes = count;
  return solveModes(comm, sys.K, sys.M, rigid, req).eigenvalues;
}

ImportedModel importStage(Comm comm, const BodySpec& spec, bool quiet) {
  const int rank = commRank(comm);
  const MatricesSpec& ms = *spec.matrices;
  ImportedModel model = importMatrices(ms);
  const bool speak = rank == 0 && !quiet;
  const MassProjection p = rigidMassProjection(model.mesh.nodes, model.M);
  long solid = 0;
  for (char s : model.solid) solid += s;
  if (speak) {
    std::printf("fe-prep: imported %s matrices: %ld DOF on %ld nodes (%ld solid with 3 DOF, %ld with 6), units %s\n",
                ms.format.c_str(), model.source_dofs, model.mesh.nodeCount(), solid, model.mesh.nodeCount() - solid,
                ms.units.name.c_str());
    std::printf("  stiffness %s, mass %s, indices %s; rigid motions strain K by %.1e (relative)\n",
                model.storage_K.c_str(), model.storage_M.c_str(), model.indexing.c_str(), model.rigid_strain);
    const Eigen::Vector3d c = p.centerOfMass();
    const Eigen::Matrix3d& J = p.inertia_about_origin;
    std::printf("  M's rigid-body projection: mass %.9g kg, centre [%.9g, %.9g, %.9g] m\n", p.mass, c.x(), c.y(), c.z());
    std::printf("    inertia about the origin [kg m^2]: [[%.9g, %.9g, %.9g], [%.9g, %.9g, %.9g], [%.9g, %.9g, %.9g]]\n",
                J(0, 0), J(0, 1), J(0, 2), J(1, 0), J(1, 1), J(1, 2), J(2, 0), J(2, 1), J(2, 2));
  }
  // The translational block of R^T M R is m I for any mass matrix that moves
  // rigidly with its nodes; a departure means the matrix and the nodes disagree.
  if (rank == 0 && p.misfit > 1e-6)
    std::fprintf(stderr, "fe-prep: warning: %s: the mass matrix's rigid translations do not share one mass (the "
                 "translational block of R^T M R departs from m I by %.2e relative): the matrix and the node "
                 "coordinates of %s disagree\n", ms.mass.c_str(), p.misfit, ms.model.c_str());
  if (!ms.reference_frequencies.empty()) {
    // The source's table (CalculiX *FREQUENCY of the same free model) in its
    // time unit; its rigid modes (|lambda| below 1e-6 of the largest) skipped.
    const Eigen::VectorXd src_all = readCalculixEigenvalues(ms.reference_frequencies) / (ms.units.time * ms.units.time);
    const double top = src_all.cwiseAbs().maxCoeff();
    std::vector<double> src;
    for (long i = 0; i < src_all.size(); ++i)
      if (std::abs(src_all(i)) > 1e-6 * top) src.push_back(src_all(i));
    const long count = std::min<long>(static_cast<long>(src.size()), 20);
    const Eigen::VectorXd mine = importedFreeEigenvalues(comm, model, count);
    if (speak) std::printf("  %-5s %16s %16s %10s   (free model; source: %s)\n", "mode", "imported [Hz]", "source [Hz]", "rel. diff",
                           ms.reference_frequencies.c_str());
    for (long j = 0; j < std::min<long>(count, mine.size()); ++j) {
      const double f = std::sqrt(std::max(mine(j), 0.0)) / (2 * M_PI);
      const double g = std::sqrt(std::max(src[static_cast<std::size_t>(j)], 0.0)) / (2 * M_PI);
      const double rel = std::abs(f - g) / g;
      if (speak) std::printf("  %-5ld %16.8g %16.8g %10.2e\n", j + 1, f, g, rel);
      if (rank == 0 && rel > 1e-6)
        std::fprintf(stderr, "fe-prep: warning: elastic mode %ld of the imported matrices is at %.8g Hz, the source "
                     "(%s) has %.8g Hz: %.2e relative, beyond 1e-6\n", j + 1, f, ms.reference_frequencies.c_str(), g, rel);
    }
  }
  return model;
}

ImportedLumping importedLumping(Comm comm, const ImportedModel& model, bool quiet) {
  const int rank = commRank(comm);
  const MassProjection p = rigidMassProjection(model.mesh.nodes, model.M);
  ImportedLumping l = importedNodalMasses(model.mesh.nodes, model.M, p);
  if (rank == 0 && !l.applied)
    std::fprintf(stderr, "fe-prep: warning: no positive nodal masses reproduce the imported mass matrix's centre and "
                 "inertia (a nodal mass would fall to %.2f of its diagonal share); /mass/nodal keeps the scaled "
                 "diagonal and /inertia/exact the matrix's values\n", l.min_ratio);
  (void)quiet;
  return l;
}

RigidProperties importedRigidProperties(const ImportedModel& model) {
  const MassProjection p = rigidMassProjection(model.mesh.nodes, model.M);
  RigidProperties r;
  r.mass = p.mass;
  r.first_moment = p.first_moment;
  // The second moment whose tr(E) I - E is the projection's inertia (rotary terms included).
  const Eigen::Matrix3d& J = p.inertia_about_origin;
  r.second_moment = 0.5 * J.trace() * Eigen::Matrix3d::Identity() - J;
  return r;
}

std::string checkImportedInterface(const ImportedModel& model, MeshInterface& mi, const InterfaceSpec& spec) {
  if (mi.coupling == Coupling::Node && model.solid[static_cast<std::size_t>(mi.node)])
    spec.node.fail("interface '" + spec.name + "' would attach to node " +
                   std::to_string(model.labels[static_cast<std::size_t>(mi.node)]) +
                   ", a solid node without rotations; give it a patch: {point: [...], coupling: distributing or rigid, "
                   "nodes: {within: R | box: [...] | edge: NSET}}");
  if (mi.coupling != Coupling::Distributing) return "";
  long faces = 0;
  double area = 0.0;
  const Eigen::VectorXd w = patchFaceWeights(model.mesh.nodes, model.faces, mi.nodes, &faces, &area);
  char buf[256];
  if (faces > 0) {
    mi.weights = w;
    long carried = 0;
    for (long i = 0; i < w.size(); ++i) carried += w(i) != 0.0 ? 1 : 0;
    std::snprintf(buf, sizeof buf, "interface '%s': distributing patch of %zu nodes weighted by %ld solid faces "
                  "(%.6g m^2; %ld nodes carry area, the others weigh 0)", spec.name.c_str(), mi.nodes.size(), faces, area, carried);
  } else {
    // No element face lies wholly in the patch (6-DOF nodes of shells or beams,
    // whose faces the import does not build, or a patch narrower than one face).
    mi.weights = Eigen::VectorXd::Ones(static_cast<long>(mi.nodes.size()));
    std::snprintf(buf, sizeof buf, "interface '%s': distributing patch of %zu nodes weighted equally (no solid element "
                  "face lies wholly in the patch)", spec.name.c_str(), mi.nodes.size());
  }
  mi.W = distributingMap(model.mesh, mi.nodes, mi.weights, mi.point);
  return buf;
}

}  // namespace fc::feprep
