#include "fe-prep/interfaces.h"

#include <algorithm>
#include <cmath>

#include "fe-prep/reference_conditions.h"

namespace fc::feprep {

Eigen::VectorXd tributaryWeights(const Mesh& mesh, const std::vector<long>& nodes) {
  Eigen::VectorXd all = Eigen::VectorXd::Zero(mesh.nodeCount());
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d a = mesh.nodes.row(t[0]), b = mesh.nodes.row(t[1]), c = mesh.nodes.row(t[2]);
    const double A = 0.5 * (b - a).cross(c - a).norm();
    for (long k : t) all(k) += A / 3.0;
  }
  for (const auto& e : mesh.beams) {
    const double L = (mesh.nodes.row(e[1]) - mesh.nodes.row(e[0])).norm();
    for (long k : e) all(k) += L / 2.0;
  }
  Eigen::VectorXd w(static_cast<long>(nodes.size()));
  for (std::size_t i = 0; i < nodes.size(); ++i) w(static_cast<long>(i)) = all(nodes[i]);
  return w;
}

Eigen::VectorXd patchAreaWeights(const Mesh& mesh, const std::vector<long>& nodes) {
  std::vector<long> slot(static_cast<std::size_t>(mesh.nodeCount()), -1);
  for (std::size_t i = 0; i < nodes.size(); ++i) slot[static_cast<std::size_t>(nodes[i])] = static_cast<long>(i);
  Eigen::VectorXd w = Eigen::VectorXd::Zero(static_cast<long>(nodes.size()));
  bool any = false;
  for (const auto& t : mesh.triangles) {
    if (slot[static_cast<std::size_t>(t[0])] < 0 || slot[static_cast<std::size_t>(t[1])] < 0 ||
        slot[static_cast<std::size_t>(t[2])] < 0)
      continue;
    const Eigen::Vector3d a = mesh.nodes.row(t[0]), b = mesh.nodes.row(t[1]), c = mesh.nodes.row(t[2]);
    const double A = 0.5 * (b - a).cross(c - a).norm();
    for (long k : t) w(slot[static_cast<std::size_t>(k)]) += A / 3.0;
    any = true;
  }
  return any ? w : tributaryWeights(mesh, nodes);
}

Eigen::MatrixXd distributingMap(const Mesh& mesh, const std::vector<long>& nodes, const Eigen::VectorXd& weights,
                                const Eigen::Vector3d& P) {
  const long p = static_cast<long>(nodes.size());
  double Lc2 = 0.0;
  for (long k : nodes) Lc2 = std::max(Lc2, (mesh.nodes.row(k).transpose() - P).squaredNorm());
  Eigen::Matrix<double, 6, 6> A = Eigen::Matrix<double, 6, 6>::Zero();
  std::vector<Eigen::Matrix<double, 3, 6>> G(static_cast<std::size_t>(p));
  for (long i = 0; i < p; ++i) {
    G[static_cast<std::size_t>(i)] = rigidTransfer(mesh.nodes.row(nodes[static_cast<std::size_t>(i)]).transpose() - P).topRows<3>();
    A += weights(i) * G[static_cast<std::size_t>(i)].transpose() * G[static_cast<std::size_t>(i)];
  }
  // Rotation columns scaled by the patch size for the rank test.
  const double Lc = std::sqrt(std::max(Lc2, 1e-24));
  Eigen::Matrix<double, 6, 6> S = Eigen::Matrix<double, 6, 6>::Identity();
  S.bottomRightCorner<3, 3>() *= 1.0 / std::max(Lc, 1e-12);
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>> es(S * A * S);
  // The rotations the translations leave undetermined: the rotation parts of
  // A's null vectors (about the line of collinear nodes; all three for one
  // node). Only those join the fit: a shell's drilling rotation (about its
  // normal, a fictitious stiffness and no mass) must not, or the point's
  // in-plane rotation of an edge patch would follow the drilling DOF (a
  // massless, nearly free boundary DOF: docs/fe-prep.md, Craig-Bampton).
  Eigen::MatrixXd null_rot(3, 0);
  for (int k = 0; k < 6; ++k)
    if (es.eigenvalues()(k) < 1e-8 * es.eigenvalues()(5)) {
      null_rot.conservativeResize(3, null_rot.cols() + 1);
      null_rot.rightCols(1) = es.eigenvectors().col(k).tail<3>();
    }
  const bool rotations = null_rot.cols() > 0;
  Eigen::Matrix3d Pd = Eigen::Matrix3d::Zero();  // projector onto the undetermined rotations
  if (rotations) {
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(null_rot, Eigen::ComputeThinU);
    for (long k = 0; k < svd.singularValues().size(); ++k)
      if (svd.singularValues()(k) > 1e-8 * svd.singularValues()(0)) Pd += svd.matrixU().col(k) * svd.matrixU().col(k).transpose();
  }
  const double wr = rotations ? std::max(Lc2, 1e-24) : 0.0;
  if (rotations) A.bottomRightCorner<3, 3>() += wr * weights.sum() * Pd;
  const Eigen::Matrix<double, 6, 6> Ainv = A.inverse();
  Eigen::MatrixXd W = Eigen::MatrixXd::Zero(6, 6 * p);
  for (long i = 0; i < p; ++i) {
    W.block(0, 6 * i, 6, 3) = weights(i) * Ainv * G[static_cast<std::size_t>(i)].transpose();
    if (rotations) W.block(0, 6 * i + 3, 6, 3) = weights(i) * wr * Ainv.rightCols<3>() * Pd;
  }
  return W;
}

MeshInterface resolveInterface(const Mesh& mesh, const InterfaceSpec& s, const Eigen::Vector3d& projection) {
  MeshInterface it;
  it.name = s.name;
  it.point = s.position;
  it.coupling = s.coupling;
  it.node = mesh.nearestNode(projection);
  if (s.coupling == Coupling::Node) return it;
  switch (s.select) {
    case PatchSelect::Within:
      for (long k = 0; k < mesh.nodeCount(); ++k)
        if ((mesh.nodes.row(k).transpose() - projection).norm() <= s.within * (1 + 1e-12)) it.nodes.push_back(k);
      break;
    case PatchSelect::Edge:
    case PatchSelect::Set: {
      auto e = mesh.sets.find(s.edge);
      if (e == mesh.sets.end() || e->second.empty()) {
        std::vector<std::string> known;
        for (const auto& kv : mesh.sets) known.push_back(kv.first);
        s.nodes_node.fail("the mesh has no node set '" + s.edge + "'" + didYouMean(s.edge, known));
      }
      it.nodes = e->second;
      break;
    }
    case PatchSelect::Box:
      for (long k = 0; k < mesh.nodeCount(); ++k) {
        const Eigen::Vector3d x = mesh.nodes.row(k).transpose();
        if ((x.array() >= s.box_lo.array() - 1e-12).all() && (x.array() <= s.box_hi.array() + 1e-12).all())
          it.nodes.push_back(k);
      }
      break;
  }
  if (it.nodes.empty())
    s.nodes_node.fail("selects no node of the mesh; expected a patch around the interface point");
  std::sort(it.nodes.begin(), it.nodes.end());
  // The master (rigid) or the first candidate for elimination (distributing): the patch node nearest the point.
  double best = 1e300;
  for (long k : it.nodes) {
    const double d = (mesh.nodes.row(k).transpose() - projection).norm();
    if (d < best) best = d, it.node = k;
  }
  if (s.coupling == Coupling::Distributing) {
    // A Nastran RBE3's own weights (its set's nodes are sorted as it.nodes are), else the tributary shares.
    if (s.given_weights.size() == static_cast<long>(it.nodes.size())) it.weights = s.given_weights;
    else it.weights = s.select == PatchSelect::Box ? patchAreaWeights(mesh, it.nodes) : tributaryWeights(mesh, it.nodes);
    it.W = distributingMap(mesh, it.nodes, it.weights, it.point);
  }
  return it;
}

Eigen::MatrixXd interfaceLoads(const MeshInterface& it, const Mesh& mesh) {
  Eigen::MatrixXd F = Eigen::MatrixXd::Zero(6 * mesh.nodeCount(), 6);
  if (it.coupling == Coupling::Distributing) {
    for (std::size_t i = 0; i < it.nodes.size(); ++i)
      F.middleRows(6 * it.nodes[i], 6) = it.W.middleCols(6 * static_cast<long>(i), 6).transpose();
  } else {
    F.middleRows(6 * it.node, 6) = rigidTransfer(it.point - mesh.nodes.row(it.node).transpose()).transpose();
  }
  return F;
}

Eigen::MatrixXd referencePointShapes(const MeshInterface& it, const Mesh& mesh, const Eigen::MatrixXd& q) {
  const long nm = q.cols();
  Eigen::MatrixXd s(nm, 6);
  if (it.coupling == Coupling::Distributing) {
    Eigen::MatrixXd qp(6 * static_cast<long>(it.nodes.size()), nm);
    for (std::size_t i = 0; i < it.nodes.size(); ++i) qp.middleRows(6 * static_cast<long>(i), 6) = q.middleRows(6 * it.nodes[i], 6);
    return (it.W * qp).transpose();
  }
  // Node and Rigid: the point rigidly attached to its node.
  const Eigen::Matrix<double, 6, 6> G = rigidTransfer(it.point - mesh.nodes.row(it.node).transpose());
  return (G * q.middleRows(6 * it.node, 6)).transpose();
}

}  // namespace fc::feprep
