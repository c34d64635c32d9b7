#include "mbs-run/monitors/stress_recovery.h"
#include "mbs-run/monitors/stress_recovery_mixed.h"

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

namespace {

// The beams' ply stresses, Tsai-Wu and Hashin indices at their stations from
// their midpoint section forces `forces` (n_el, 6): stations (n_el, 3) x
// section elements (ns) x [s_11, s_22, t_12], C order.
void beamPlies(const BodyStressRecovery& r, long ns, const Eigen::VectorXd& forces, Eigen::VectorXd& ply,
               Eigen::VectorXd& fi, Eigen::VectorXd& hs) {
  const long ne = r.beam_lengths.size();
  ply.resize(3 * 3 * ne * ns);
  fi.setZero(3 * ne * ns);
  hs.setZero(4 * 3 * ne * ns);
  for (long e = 0; e < ne; ++e) {
    const Vector6d mid = forces.segment<6>(6 * e);
    for (int j = 0; j < 3; ++j) {
      const long st = 3 * e + j;
      const Vector6d R = resultantsAtStation(mid, 0.5 * (j - 1) * r.beam_lengths(e));
      ply.segment(3 * ns * st, 3 * ns).noalias() = r.section_ply * R;
      for (long k = 0; k < ns; ++k)
        if (r.section_has_strength[static_cast<std::size_t>(k)]) {
          const Eigen::Vector3d sk = ply.segment<3>(3 * (st * ns + k));
          fi(st * ns + k) = tsaiWuIndex(r.section_tsai_wu[static_cast<std::size_t>(k)], sk);
          const HashinIndices x = hashinIndices(r.section_strength[static_cast<std::size_t>(k)], sk);
          hs.segment<4>(4 * (st * ns + k)) << x.fibre_tension, x.fibre_compression, x.matrix_tension, x.matrix_compression;
        }
    }
  }
}

}  // namespace

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
  // A mixed body's beams (stressRecovery): their outputs follow the shells'.
  if (kind == Kind::Shell && beam_resultants.rows() > 0) {
    const std::size_t k = mixedShellOutputs(*this);
    fields[k] = beamSectionForces(beam_resultants, q);
    if (section_ply.rows() > 0)
      beamPlies(*this, section_ply.rows() / 3, fields[k], fields[k + 1], fields[k + 2], fields[k + 3]);
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
  beamPlies(*this, n_plies, fields[0], fields[static_cast<std::size_t>(ply_output)],
            fields[static_cast<std::size_t>(failure_output)], fields[static_cast<std::size_t>(hashin_output)]);
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

std::size_t mixedShellOutputs(const BodyStressRecovery& r) {
  if (r.kind != BodyStressRecovery::Kind::Shell || r.beam_resultants.rows() == 0) return 0;
  return r.failure_output >= 0 ? 3 : 1;  // ply_stress [, failure_index, hashin] (shellStressRecovery)
}

const Eigen::VectorXd* sectionForcesField(const BodyStressRecovery& r, const std::vector<Eigen::VectorXd>& fields) {
  if (fields.size() != r.outputs.size()) return nullptr;
  if (r.kind == BodyStressRecovery::Kind::Beam) return &fields[0];
  if (r.beam_part) return &fields[mixedShellOutputs(r)];
  return nullptr;
}

std::shared_ptr<const BodyStressRecovery> stressRecovery(const StressRecoveryData& d, const std::string& file) {
  if (!d.hasShell() || !d.hasBeam()) return d.hasBeam() ? beamStressRecovery(d, file) : shellStressRecovery(d, file);
  // A mixed body: its triangles as a shell body's, its beams as a beam body's
  // (their midpoints are the centroids' last rows), the two in one recovery.
  const long nb = d.beam_resultants.rows() / 6, nt = d.centroids.rows() - nb;
  if (nb <= 0 || nt <= 0 || d.shell_strains.rows() != 6 * nt)
    throw std::invalid_argument(file + ": a body of shells and beams needs (n_triangles + n_beams) centroids, " +
                                std::to_string(d.centroids.rows()) + " for " + std::to_string(d.shell_strains.rows() / 6) +
                                " triangles and " + std::to_string(nb) + " beams");
  StressRecoveryData shells;
  shells.centroids = d.centroids.topRows(nt);
  shells.shell_strains = d.shell_strains;
  shells.plies = d.plies;
  StressRecoveryData beams;
  beams.centroids = d.centroids.bottomRows(nb);
  beams.beam_resultants = d.beam_resultants;
  beams.section = d.section;
  beams.beam_lengths = d.beam_lengths;
  beams.beam_stations = d.beam_stations;
  auto r = std::make_shared<BodyStressRecovery>(*shellStressRecovery(shells, file));
  const auto b = beamStressRecovery(beams, file);
  r->beam_part = b;
  r->beam_resultants = b->beam_resultants;
  r->section_ply = b->section_ply;
  r->beam_lengths = b->beam_lengths;
  r->stations = b->stations;
  r->section_has_strength = b->section_has_strength;
  r->section_tsai_wu = b->section_tsai_wu;
  r->section_strength = b->section_strength;
  for (const StressOutput& o : b->outputs)
    r->outputs.push_back({o.name == "section_forces" ? o.name : "beam_" + o.name, o.dims});
  return r;
}

std::shared_ptr<const BodyStressRecovery> loadStressRecovery(const std::string& body_file, int n_modes) {
  return stressRecovery(readStressData(body_file, n_modes), body_file);
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
