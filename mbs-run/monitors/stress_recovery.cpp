#include "mbs-run/monitors/stress_recovery.h"

#include <cmath>
#include <stdexcept>

#include "common/flexbody.h"
#include "common/h5io.h"
#include "mbs-run/mechanics/flexible/section_forces.h"

namespace fc::mbs {

Eigen::Vector3d strainAtHeight(const Vector6d& e, double z) { return e.head<3>() + z * e.tail<3>(); }

Eigen::Matrix3d strainToPlyAxes(double a) {
  const double c = std::cos(a), s = std::sin(a);
  Eigen::Matrix3d T;
  T << c * c, s * s, c * s,
       s * s, c * c, -c * s,
       -2 * c * s, 2 * c * s, c * c - s * s;
  return T;
}

TsaiWu tsaiWuCoefficients(const Strength5& st) {
  if (!(st.array() > 0).all()) throw std::invalid_argument("Tsai-Wu: every strength must be positive");
  const double Xt = st(0), Xc = st(1), Yt = st(2), Yc = st(3), S = st(4);
  TsaiWu c;
  c.F1 = 1 / Xt - 1 / Xc;
  c.F2 = 1 / Yt - 1 / Yc;
  c.F11 = 1 / (Xt * Xc);
  c.F22 = 1 / (Yt * Yc);
  c.F66 = 1 / (S * S);
  c.F12 = -0.5 * std::sqrt(c.F11 * c.F22);
  return c;
}

PlyStrength plyStrength(const Strength5& st) { return {st(0), st(1), st(2), st(3), st(4)}; }

double tsaiWuIndex(const TsaiWu& c, const Eigen::Vector3d& s) {
  return c.F1 * s(0) + c.F2 * s(1) + c.F11 * s(0) * s(0) + c.F22 * s(1) * s(1) + c.F66 * s(2) * s(2) +
         2 * c.F12 * s(0) * s(1);
}

Eigen::MatrixXd plyStressOperator(const PlyTable& plies) {
  const long np = plies.size();
  Eigen::MatrixXd P(3 * np, 6);
  for (long k = 0; k < np; ++k) {
    const Eigen::Matrix3d QT = plies.stiffness[static_cast<std::size_t>(k)] * strainToPlyAxes(plies.angle_deg(k) * M_PI / 180.0);
    P.block<3, 3>(3 * k, 0) = QT;
    P.block<3, 3>(3 * k, 3) = plies.z_mid(k) * QT;
  }
  return P;
}

long StressOutput::size() const {
  long n = 1;
  for (long d : dims) n *= d;
  return n;
}

void BodyStressRecovery::recover(const Eigen::VectorXd& q, std::vector<Eigen::VectorXd>& fields) const {
  fields.resize(outputs.size());
  switch (kind) {
    case Kind::Shell: {
      // Generalised strains of every element at once, (6, n_el) column-major,
      // then every ply of every element in one product: column e of
      // P E holds element e's plies' [s1, s2, t12] one after another, which is
      // the C order (n_el, n_plies, 3) of /bodies/NAME/ply_stress.
      const Eigen::VectorXd e = shell_strains * q;
      const Eigen::Map<const Eigen::MatrixXd> E(e.data(), 6, n_elements);
      fields[0].resize(3 * n_plies * n_elements);
      Eigen::Map<Eigen::MatrixXd>(fields[0].data(), 3 * n_plies, n_elements).noalias() = ply_operator * E;
      if (failure_output >= 0) {
        Eigen::VectorXd& f = fields[static_cast<std::size_t>(failure_output)];
        f.resize(n_plies * n_elements);
        const double* s = fields[0].data();
        for (long el = 0; el < n_elements; ++el)
          for (long k = 0; k < n_plies; ++k, s += 3)
            f(el * n_plies + k) = tsaiWuIndex(tsai_wu[static_cast<std::size_t>(k)], Eigen::Vector3d(s[0], s[1], s[2]));
      }
      if (hashin_output >= 0) {
        Eigen::VectorXd& h = fields[static_cast<std::size_t>(hashin_output)];
        h.resize(4 * n_plies * n_elements);
        const double* s = fields[0].data();
        for (long i = 0; i < n_plies * n_elements; ++i, s += 3) {
          const HashinIndices x = hashinIndices(ply_strength[static_cast<std::size_t>(i % n_plies)], Eigen::Vector3d(s[0], s[1], s[2]));
          h.segment<4>(4 * i) << x.fibre_tension, x.fibre_compression, x.matrix_tension, x.matrix_compression;
        }
      }
      break;
    }
    case Kind::Beam:
      // Element-major (n_el, 6), the C order of /bodies/NAME/section_forces.
      fields[0] = beamSectionForces(beam_resultants, q);
      if (section_ply.rows() > 0) recoverBeamPlies(fields);
      break;
  }
}

std::shared_ptr<const BodyStressRecovery> shellStressRecovery(const StressRecoveryData& d, const std::string& file) {
  if (!d.hasShell()) throw std::invalid_argument(file + ": no shell stress recovery data");
  auto r = std::make_shared<BodyStressRecovery>();
  r->kind = BodyStressRecovery::Kind::Shell;
  r->file = file;
  r->n_elements = d.centroids.rows();
  r->n_plies = d.plies.size();
  r->shell_strains = d.shell_strains;
  r->ply_operator = plyStressOperator(d.plies);
  r->outputs.push_back({"ply_stress", {r->n_elements, r->n_plies, 3}});
  if (d.plies.hasStrength()) {
    for (long k = 0; k < r->n_plies; ++k) {
      r->tsai_wu.push_back(tsaiWuCoefficients(d.plies.strength.row(k).transpose()));
      r->ply_strength.push_back(plyStrength(d.plies.strength.row(k).transpose()));
    }
    r->failure_output = static_cast<int>(r->outputs.size());
    r->outputs.push_back({"failure_index", {r->n_elements, r->n_plies}});
    r->hashin_output = static_cast<int>(r->outputs.size());
    r->outputs.push_back({"hashin", {r->n_elements, r->n_plies, 4}});
  }
  return r;
}

Vector6d resultantsAtStation(const Vector6d& mid, double s) {
  Vector6d r = mid;
  r(4) += s * mid(2);
  r(5) -= s * mid(1);
  return r;
}

void BodyStressRecovery::recoverBeamPlies(std::vector<Eigen::VectorXd>& fields) const {
  // Stations (n_el, 3) x section elements (n_se) x [s_11, s_22, t_12], C order.
  const long ns = n_plies, ne = beam_lengths.size();
  Eigen::VectorXd& ply = fields[static_cast<std::size_t>(ply_output)];
  Eigen::VectorXd& fi = fields[static_cast<std::size_t>(failure_output)];
  Eigen::VectorXd& hs = fields[static_cast<std::size_t>(hashin_output)];
  ply.resize(3 * 3 * ne * ns);
  fi.setZero(3 * ne * ns);
  hs.setZero(4 * 3 * ne * ns);
  for (long e = 0; e < ne; ++e) {
    const Vector6d mid = fields[0].segment<6>(6 * e);
    for (int j = 0; j < 3; ++j) {
      const long st = 3 * e + j;
      const Vector6d R = resultantsAtStation(mid, 0.5 * (j - 1) * beam_lengths(e));
      ply.segment(3 * ns * st, 3 * ns).noalias() = section_ply * R;
      for (long k = 0; k < ns; ++k)
        if (section_has_strength[static_cast<std::size_t>(k)]) {
          const Eigen::Vector3d sk = ply.segment<3>(3 * (st * ns + k));
          fi(st * ns + k) = tsaiWuIndex(section_tsai_wu[static_cast<std::size_t>(k)], sk);
          const HashinIndices x = hashinIndices(section_strength[static_cast<std::size_t>(k)], sk);
          hs.segment<4>(4 * (st * ns + k)) << x.fibre_tension, x.fibre_compression, x.matrix_tension, x.matrix_compression;
        }
    }
  }
}

std::shared_ptr<const BodyStressRecovery> beamStressRecovery(const StressRecoveryData& d, const std::string& file) {
  if (!d.hasBeam()) throw std::invalid_argument(file + ": no beam section resultants");
  auto r = std::make_shared<BodyStressRecovery>();
  r->kind = BodyStressRecovery::Kind::Beam;
  r->file = file;
  r->n_elements = d.centroids.rows();
  r->beam_resultants = d.beam_resultants;
  r->outputs.push_back({"section_forces", {r->n_elements, 6}});
  if (d.section.empty()) return r;
  // Ply stresses and Tsai-Wu at the stations from the section's basis. A ply
  // material without strengths is an error (the index is what was asked for);
  // an isotropic element without them gets stresses and an index of 0.
  const SectionStressBasis& s = d.section;
  const long ns = s.size();
  r->n_plies = ns;
  r->section_ply = s.ply_stress;
  r->beam_lengths = d.beam_lengths;
  r->stations = d.beam_stations;
  r->section_has_strength.assign(static_cast<std::size_t>(ns), 0);
  r->section_tsai_wu.resize(static_cast<std::size_t>(ns));
  r->section_strength.resize(static_cast<std::size_t>(ns));
  for (long k = 0; k < ns; ++k) {
    const Strength5 st = s.strength.row(k).transpose();
    if ((st.array() > 0).all()) {
      r->section_has_strength[static_cast<std::size_t>(k)] = 1;
      r->section_tsai_wu[static_cast<std::size_t>(k)] = tsaiWuCoefficients(st);
      r->section_strength[static_cast<std::size_t>(k)] = plyStrength(st);
    } else if (s.has_plies[static_cast<std::size_t>(k)]) {
      throw std::invalid_argument(file + ": the beam's section material '" + s.material[static_cast<std::size_t>(k)] +
                                  "' has no strengths: outputs.stresses needs them for the Tsai-Wu index of its plies; "
                                  "give it strength: {Xt, Xc, Yt, Yc, S12} and rerun section-prep and fe-prep");
    }
  }
  const long n_st = 3 * r->n_elements;
  r->ply_output = static_cast<int>(r->outputs.size());
  r->outputs.push_back({"ply_stress", {n_st, ns, 3}});
  r->failure_output = static_cast<int>(r->outputs.size());
  r->outputs.push_back({"failure_index", {n_st, ns}});
  r->hashin_output = static_cast<int>(r->outputs.size());
  r->outputs.push_back({"hashin", {n_st, ns, 4}});
  return r;
}

std::shared_ptr<const BodyStressRecovery> loadStressRecovery(const std::string& body_file, int n_modes) {
  const StressRecoveryData d = readStressData(body_file, n_modes);
  return d.hasBeam() ? beamStressRecovery(d, body_file) : shellStressRecovery(d, body_file);
}

FailureLocation largestFailureIndex(const BodyStressRecovery& r, const Eigen::VectorXd& f) {
  FailureLocation out;
  if (f.size() == 0 || r.n_plies == 0) return out;
  Eigen::Index i = 0;
  out.value = f.maxCoeff(&i);
  out.element = static_cast<long>(i) / r.n_plies;
  out.ply = static_cast<long>(i) % r.n_plies;
  return out;
}

}  // namespace fc::mbs
