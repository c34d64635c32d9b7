#include "mbs-run/output/results.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <iomanip>
#include <sstream>
#include <stdexcept>

#include "common/files.h"
#include "mbs-run/mechanics/flexible/flexible_body.h"
#include "mbs-run/mechanics/flexible/modal.h"
#include "mbs-run/monitors/stress_recovery.h"
#include "mbs-run/run/run_policy.h"

namespace fc::mbs {

std::string distanceChannel(const Model& m, std::size_t k) {
  return "distances/" + m.bodies[m.distance_pairs[k][0]].name + "-" + m.bodies[m.distance_pairs[k][1]].name;
}

std::vector<Channel> resultChannels(const Model& m) {
  std::vector<Channel> c;
  auto vec3 = [&](const std::string& name, auto get) {
    c.push_back({name, 3, false, [get](const Sample& s, double* out) {
                   const Eigen::Vector3d v = get(s);
                   for (int i = 0; i < 3; ++i) out[i] = v[i];
                 }});
  };
  auto scalar = [&](const std::string& name, auto get) {
    c.push_back({name, 1, true, [get](const Sample& s, double* out) { out[0] = get(s); }});
  };
  scalar("time", [](const Sample& s) { return s.time; });
  // The rows the full stress fields hold, when outputs.stress_every is given.
  if (m.stress_every > 0) {
    scalar("stress_time", [](const Sample& s) { return s.time; });
    c.back().decimated = true;
  }
  for (std::size_t k = 0; k < m.bodies.size(); ++k) {
    const std::string b = "bodies/" + m.bodies[k].name + "/";
    vec3(b + "position", [k](const Sample& s) { return s.bodies[k].position; });
    c.push_back({b + "orientation", 4, false, [k](const Sample& s, double* out) {
                   for (int i = 0; i < 4; ++i) out[i] = s.bodies[k].orientation[i];
                 }});
    vec3(b + "velocity", [k](const Sample& s) { return s.bodies[k].velocity; });
    vec3(b + "angular_velocity", [k](const Sample& s) { return s.bodies[k].angular_velocity; });
    const int nm = m.bodies[k].modes;
    if (nm > 0) {
      c.push_back({b + "modal_coordinates", nm, false, [k, nm](const Sample& s, double* out) {
                     for (int i = 0; i < nm; ++i) out[i] = s.bodies[k].modal[i];
                   }});
      c.push_back({b + "modal_velocities", nm, false, [k, nm](const Sample& s, double* out) {
                     for (int i = 0; i < nm; ++i) out[i] = s.bodies[k].modal_rate[i];
                   }});
      const ModalProperties modal = m.bodies[k].flex->modal;
      c.push_back({b + "modal_energy", nm, false, [k, nm, modal](const Sample& s, double* out) {
                     const Eigen::VectorXd e = modalEnergies(modal, s.bodies[k].modal, s.bodies[k].modal_rate);
                     for (int i = 0; i < nm; ++i) out[i] = e[i];
                   }});
      // Craig-Bampton bodies: each kept fixed-interface mode's strain energy
      // per row, to rank them over any time window (flexible_body.h).
      if (m.bodies[k].flex->fixed_interface_coordinates.size()) {
        const auto flex = m.bodies[k].flex;
        const long nf = flex->fixed_interface_eigenvalues.size();
        c.push_back({b + "fixed_interface_energy", static_cast<int>(nf), false, [k, nf, flex](const Sample& s, double* out) {
                       const Eigen::VectorXd e = fixedInterfaceStrainEnergies(*flex, s.bodies[k].modal);
                       for (long i = 0; i < nf; ++i) out[i] = e[i];
                     }});
      }
    }
    // Stress recovery of the bodies named in outputs.stresses: one dataset per
    // output, the time leading (e.g. ply_stress (n_out, n_el, n_plies, 3)).
    if (const auto& r = m.bodies[k].stress)
      for (std::size_t i = 0; i < r->outputs.size(); ++i) {
        const StressOutput& o = r->outputs[i];
        const long n = o.size();
        c.push_back({b + o.name, static_cast<int>(n), false,
                     [k, i, n](const Sample& s, double* out) {
                       const Eigen::VectorXd& f = s.bodies[k].stress[i];
                       std::copy(f.data(), f.data() + n, out);
                     },
                     std::vector<hsize_t>(o.dims.begin(), o.dims.end()), m.stress_every > 1});
      }
  }
  for (std::size_t j = 0; j < m.joints.size(); ++j) {
    const std::string p = "joints/" + m.joints[j].name + "/";
    if (m.joints[j].type == JointType::Revolute) scalar(p + "angle", [j](const Sample& s) { return s.joints[j].angle; });
    vec3(p + "reaction_force", [j](const Sample& s) { return s.joints[j].reaction_force; });
    // A spherical joint transmits no moment (contracts.md: reaction_torque for
    // every joint that does).
    if (m.joints[j].type != JointType::Spherical)
      vec3(p + "reaction_torque", [j](const Sample& s) { return s.joints[j].reaction_torque; });
    if (m.joints[j].limits.any()) {
      scalar(p + "limit_state", [j](const Sample& s) { return double(s.joints[j].limit_state); });
      scalar(p + "limit_torque", [j](const Sample& s) { return s.joints[j].limit_torque; });
    }
  }
  for (std::size_t k = 0; k < m.distance_pairs.size(); ++k)
    scalar(distanceChannel(m, k), [k](const Sample& s) { return s.distances[k]; });
  // Contact force elements: contacts/NAME/force [N] and penetration [m].
  const std::vector<int> contacts = m.contactElements();
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    const std::string p = "contacts/" + m.forces[static_cast<std::size_t>(contacts[k])].name + "/";
    scalar(p + "force", [k](const Sample& s) { return s.contact_force[k]; });
    scalar(p + "penetration", [k](const Sample& s) { return s.contact_penetration[k]; });
  }
  scalar("energy/kinetic", [](const Sample& s) { return s.energy.kinetic; });
  scalar("energy/potential", [](const Sample& s) { return s.energy.potential; });
  scalar("energy/strain", [](const Sample& s) { return s.energy.strain; });
  scalar("energy/dissipated", [](const Sample& s) { return s.energy.dissipated; });
  scalar("energy/applied_work", [](const Sample& s) { return s.energy.applied_work; });
  scalar("diagnostics/constraint_violation", [](const Sample& s) { return s.violation; });
  return c;
}

namespace {

// The buffer of rows written at once: about 1 MB whatever the model's width,
// which also bounds what a stopped run can lose to a SIGKILL since the last flush.
constexpr unsigned long long kBlockBytes = 1ull << 20;
constexpr double kFlushSeconds = 10.0;

// Each contact element's largest force and penetration with when, on its
// datasets; the largest force of all at the root (contact_force_max, _time, _name).
// One attribute per log. HDF5 keeps attributes in the object header, which
// holds at most 64 kB: a long log (the SAR with rigid trusses logs 3178 impacts
// on hinge H23's stop, 472 kB) made the whole results file fail to write. The
// log is cut below that, saying how much was left out (stdout has it all).
std::string joined(const std::vector<std::string>& lines) {
  constexpr std::size_t kMaxBytes = 60000;
  std::string s;
  for (std::size_t k = 0; k < lines.size(); ++k) {
    if (s.size() + lines[k].size() + 1 > kMaxBytes) {
      s += "... and " + std::to_string(lines.size() - k) + " more lines (the run's summary on stdout lists them all)\n";
      break;
    }
    s += lines[k] + "\n";
  }
  return s;
}

void writeContactPeaks(fc::H5File& f, const Model& model, const RunSummary& r) {
  const std::vector<int> contacts = model.contactElements();
  if (contacts.empty() || r.peak_contact_force.size() != contacts.size()) return;
  std::size_t worst = 0;
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    const std::string p = "/contacts/" + model.forces[static_cast<std::size_t>(contacts[k])].name + "/";
    f.setAttribute(p + "force", "peak", r.peak_contact_force[k].value);
    f.setAttribute(p + "force", "peak_time", r.peak_contact_force[k].time);
    f.setAttribute(p + "penetration", "peak", r.peak_contact_penetration[k].value);
    f.setAttribute(p + "penetration", "peak_time", r.peak_contact_penetration[k].time);
    if (r.peak_contact_force[k].value > r.peak_contact_force[worst].value) worst = k;
  }
  f.setAttribute("/", "contact_force_max", r.peak_contact_force[worst].value);
  f.setAttribute("/", "contact_force_max_time", r.peak_contact_force[worst].time);
  f.setAttribute("/", "contact_force_max_name", model.forces[static_cast<std::size_t>(contacts[worst])].name);
}

// Stops' impacts per joint and the modes' peak energies per body.
void writeImpactsAndModalPeaks(fc::H5File& f, const Model& model, const RunSummary& r) {
  // Impacts on stops: one row per impact (time, angle rate before and after,
  // impulse, energy dissipated), written even when there were none.
  for (std::size_t j = 0; j < model.joints.size() && j < r.limit_impacts.size(); ++j) {
    if (!model.joints[j].limits.any()) continue;
    const auto& imp = r.limit_impacts[j];
    Eigen::MatrixXd m(imp.size(), 5);
    for (std::size_t k = 0; k < imp.size(); ++k)
      for (int c = 0; c < 5; ++c) m(k, c) = imp[k][c];
    f.writeMatrix("/joints/" + model.joints[j].name + "/limit_impacts", m);
  }
  // Which modes the run excited: each mode's peak energy, and the share of the
  // highest quarter of the kept modes (run_summary.h).
  for (std::size_t k = 0; k < model.bodies.size() && k < r.peak_modal_energy.size(); ++k) {
    if (r.peak_modal_energy[k].size() == 0) continue;
    const std::string g = "/bodies/" + model.bodies[k].name;
    f.writeVector(g + "/modal_energy_peak", r.peak_modal_energy[k]);
    f.setAttribute(g, "highest_modes_energy_share", highestModesEnergyShare(r.peak_modal_energy[k]));
    if (k < r.peak_fixed_interface_energy.size() && r.peak_fixed_interface_energy[k].size()) {
      f.writeVector(g + "/fixed_interface_energy_peak", r.peak_fixed_interface_energy[k]);
      f.writeIntVector(g + "/fixed_interface_modes", model.bodies[k].flex->fixed_interface_modes);
    }
  }
}

// Beam stations and the envelope of the recovered stresses.
void writeStressFields(fc::H5File& f, const Model& model, const RunSummary& r) {
  // A beam's stations, where its ply stresses are recovered (body frame).
  for (const auto& body : model.bodies)
    if (body.stress && body.stress->stations.rows() > 0)
      f.writeMatrix("/bodies/" + body.name + "/stations", body.stress->stations);
  // The envelope of the recovered stresses over every output row (stress_envelope.h).
  for (std::size_t k = 0; k < model.bodies.size() && k < r.stress_envelopes.size(); ++k) {
    if (!model.bodies[k].stress) continue;
    for (const EnvelopeDataset& d : r.stress_envelopes[k].datasets(*model.bodies[k].stress)) {
      const std::string path = "/bodies/" + model.bodies[k].name + "/" + d.name;
      const std::vector<double> v(d.values.data(), d.values.data() + d.values.size());
      if (d.dims.size() == 3) {
        f.writeArray3(path, v, d.dims[0], d.dims[1], d.dims[2]);
      } else {  // (n_el, n_plies) or (n_el, 6), C order
        using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
        f.writeMatrix(path, Eigen::Map<const RowMajor>(d.values.data(), d.dims[0], d.dims[1]));
      }
    }
  }
}

// Distances, margins, overshoots, latches and clearances (run/margins.h).
void writeMargins(fc::H5File& f, const Model& model, const RunSummary& r) {
  // Contact monitor summary: the smallest distance of each pair and when.
  for (std::size_t k = 0; k < model.distance_pairs.size() && k < r.smallest_distance.size(); ++k) {
    f.setAttribute("/" + distanceChannel(model, k), "minimum", r.smallest_distance[k].value);
    f.setAttribute("/" + distanceChannel(model, k), "time_of_minimum", r.smallest_distance[k].time);
  }
  // Margins (run/margins.h, docs/file-formats.md "Margins"): each joint's
  // peak reactions as attributes of its reaction datasets, each named beam's
  // axial compression against its Euler load, the latches' arrivals, and the
  // smallest of each over the run as root attributes.
  const Margins& mg = r.margins;
  for (std::size_t j = 0; j < model.joints.size() && j < mg.joints.size(); ++j) {
    const std::string p = "/joints/" + model.joints[j].name;
    f.setAttribute(p + "/reaction_force", "peak", mg.joints[j].force);
    f.setAttribute(p + "/reaction_force", "peak_time", mg.joints[j].force_time);
    if (model.joints[j].type != JointType::Spherical) {
      f.setAttribute(p + "/reaction_torque", "peak", mg.joints[j].moment);
      f.setAttribute(p + "/reaction_torque", "peak_time", mg.joints[j].moment_time);
    }
    if (model.joints[j].type == JointType::Revolute && r.samples > 0) {
      f.setAttribute(p + "/angle", "min", mg.joints[j].angle_min);
      f.setAttribute(p + "/angle", "min_time", mg.joints[j].angle_min_time);
      f.setAttribute(p + "/angle", "max", mg.joints[j].angle_max);
      f.setAttribute(p + "/angle", "max_time", mg.joints[j].angle_max_time);
      const double past = mg.overshoot(model, static_cast<int>(j));
      if (past >= 0.0) f.setAttribute(p + "/angle", "overshoot", past);
    }
  }
  {
    int worst = -1;
    const double largest = mg.largestOvershoot(model, &worst);
    if (worst >= 0) {
      f.setAttribute("/", "overshoot_max", largest);
      f.setAttribute("/", "overshoot_max_joint", model.joints[static_cast<std::size_t>(worst)].name);
    }
  }
  if (r.samples > 0) f.setAttribute("/", "energy_dissipated", r.energy_dissipated);
  for (std::size_t k = 0; k < model.margin_beams.size() && k < mg.beams.size(); ++k) {
    const BeamMarginSpec& b = model.margin_beams[k];
    const std::string p = "/margins/beams/" + model.bodies[static_cast<std::size_t>(b.body)].name;
    const auto& c = mg.beams[k].axial_compression;
    f.writeVector(p + "/axial_compression", Eigen::Map<const Eigen::VectorXd>(c.data(), Eigen::Index(c.size())));
    const std::string d = p + "/axial_compression";
    f.setAttribute(d, "units", std::string("N"));
    f.setAttribute(d, "EI", b.EI);
    f.setAttribute(d, "length", b.length);
    f.setAttribute(d, "ends", b.ends);
    f.setAttribute(d, "K", b.K);
    f.setAttribute(d, "euler_load", b.euler_load);
    f.setAttribute(d, "joints", model.joints[static_cast<std::size_t>(b.joint_a)].name + " " +
                                    model.joints[static_cast<std::size_t>(b.joint_b)].name);
    f.setAttribute(d, "max_compression", mg.beams[k].compression);
    f.setAttribute(d, "max_compression_time", mg.beams[k].compression_time);
    f.setAttribute(d, "max_tension", mg.beams[k].tension);
    f.setAttribute(d, "max_tension_time", mg.beams[k].tension_time);
    f.setAttribute(d, "buckling_ratio", mg.beams[k].compression / b.euler_load);
  }
  if (!model.margin_beams.empty()) {
    int worst = -1;
    const double ratio = mg.largestBucklingRatio(model, &worst);
    f.setAttribute("/", "buckling_ratio_max", ratio);
    f.setAttribute("/", "buckling_ratio_max_body",
                   model.bodies[static_cast<std::size_t>(model.margin_beams[static_cast<std::size_t>(worst)].body)].name);
  }
  {
    // Each body's peak failure index with where and when (the per-member
    // table of a deployment; beams: element = station, ply = section element).
    std::vector<const RunSummary::FailurePeak*> peaks;
    for (const auto& p : r.body_failure_peaks)
      if (p.found) peaks.push_back(&p);
    if (!peaks.empty()) {
      Eigen::MatrixXd t(Eigen::Index(peaks.size()), 4);
      std::string list;
      for (std::size_t k = 0; k < peaks.size(); ++k) {
        t.row(Eigen::Index(k)) << peaks[k]->value, peaks[k]->time, double(peaks[k]->element), double(peaks[k]->ply);
        list += (list.empty() ? "" : " ") + peaks[k]->body;
      }
      f.writeMatrix("/margins/failure_index", t);
      f.setAttribute("/margins/failure_index", "bodies", list);
      f.setAttribute("/margins/failure_index", "columns",
                     std::string("peak Tsai-Wu index, time [s], element (beams: station), ply (beams: section element); 0-based"));
    }
  }
  {
    Eigen::MatrixXd l(mg.latches.size(), 3);
    std::vector<std::string> names;
    for (std::size_t k = 0; k < mg.latches.size(); ++k) {
      l(Eigen::Index(k), 0) = mg.latches[k].time;
      l(Eigen::Index(k), 1) = mg.latches[k].angle;
      l(Eigen::Index(k), 2) = mg.latches[k].rate;
      const std::string& jn = model.joints[static_cast<std::size_t>(mg.latches[k].joint)].name;
      names.push_back(jn);
      f.setAttribute("/joints/" + jn + "/angle", "latch_time", mg.latches[k].time);
      f.setAttribute("/joints/" + jn + "/angle", "latch_rate", mg.latches[k].rate);
    }
    f.writeMatrix("/margins/latches", l);
    std::string list;
    for (const auto& n : names) list += (list.empty() ? "" : " ") + n;
    f.setAttribute("/margins/latches", "joints", list);
    f.setAttribute("/margins/latches", "columns", std::string("time [s], angle [rad], arrival rate [rad/s]"));
  }
  if (!model.distance_pairs.empty() && !r.smallest_distance.empty()) {
    std::size_t best = 0;
    for (std::size_t k = 1; k < r.smallest_distance.size(); ++k)
      if (r.smallest_distance[k].value < r.smallest_distance[best].value) best = k;
    f.setAttribute("/", "clearance_min", r.smallest_distance[best].value);
    f.setAttribute("/", "clearance_min_time", r.smallest_distance[best].time);
    f.setAttribute("/", "clearance_min_pair", distanceChannel(model, best).substr(std::string("distances/").size()));
  }
}

// The run's own figures as root attributes: cost, status, tolerances, peaks.
void writeRunAttributes(fc::H5File& f, const Model& model, const RunSummary& r) {
  f.setAttribute("/", "cpu_seconds", r.cpu_seconds);
  f.setAttribute("/", "steps", r.steps);
  f.setAttribute("/", "rejected_steps", r.rejected_steps);
  f.setAttribute("/", "status", r.status);
  f.setAttribute("/", "integrator", r.integrator);
  f.setAttribute("/", "formulation", r.formulation);
  // The tolerances actually used (scene, preset or --rtol), for studies that
  // compare runs.
  f.setAttribute("/", "rtol", model.settings.rtol);
  f.setAttribute("/", "atol", absoluteTolerance(model.settings));
  f.setAttribute("/", "output_step", model.settings.output_step);
  f.setAttribute("/", "t_reached", r.t_reached);
  f.setAttribute("/", "max_constraint_violation", r.max_violation);
  f.setAttribute("/", "max_constraint_violation_time", r.peak_violation.time);
  f.setAttribute("/", "energy_balance_error", r.energy_balance_error);
  f.setAttribute("/", "rhs_evaluations", r.evaluations);
  auto peak = [&](const std::string& name, const RunSummary::Peak& p, const char* where_key) {
    f.setAttribute("/", name, p.value);
    f.setAttribute("/", name + "_time", p.time);
    f.setAttribute("/", name + "_" + where_key, p.where);
  };
  peak("peak_reaction_force", r.peak_reaction_force, "joint");
  peak("peak_reaction_torque", r.peak_reaction_torque, "joint");
  peak("peak_modal_coordinate", r.peak_modal_coordinate, "where");
  if (r.peak_failure_index.found) {
    // Where and when the largest Tsai-Wu index occurs (element and ply 0-based).
    f.setAttribute("/", "peak_failure_index", r.peak_failure_index.value);
    f.setAttribute("/", "peak_failure_index_time", r.peak_failure_index.time);
    f.setAttribute("/", "peak_failure_index_body", r.peak_failure_index.body);
    f.setAttribute("/", "peak_failure_index_element", r.peak_failure_index.element);
    f.setAttribute("/", "peak_failure_index_ply", r.peak_failure_index.ply);
  }
  if (r.peak_section_moment.found) {
    // Where and when the largest beam bending moment |(M2, M3)| occurs (element 0-based).
    f.setAttribute("/", "peak_section_moment", r.peak_section_moment.value);
    f.setAttribute("/", "peak_section_moment_time", r.peak_section_moment.time);
    f.setAttribute("/", "peak_section_moment_body", r.peak_section_moment.body);
    f.setAttribute("/", "peak_section_moment_element", r.peak_section_moment.element);
  }
  f.setAttribute("/", "warnings", joined(r.warnings));
  f.setAttribute("/", "events", joined(r.event_log));
  f.setAttribute("/", "integrator_switches", joined(r.integrator_log));
}


hid_t createExtendible(fc::H5File& f, const Channel& c, unsigned long long chunk_rows) {
  const std::string path = "/" + c.name;
  const std::size_t slash = path.rfind('/');
  if (slash > 0) f.createGroup(path.substr(0, slash));
  // (rows), (rows, columns) or (rows, dims...): the row dimension grows.
  std::vector<hsize_t> dims{0}, maxdims{H5S_UNLIMITED}, chunk{static_cast<hsize_t>(chunk_rows)};
  const std::vector<hsize_t> trailing = !c.dims.empty() ? c.dims
                                        : c.rank1      ? std::vector<hsize_t>{}
                                                       : std::vector<hsize_t>{static_cast<hsize_t>(c.columns)};
  for (hsize_t d : trailing) {
    dims.push_back(d);
    maxdims.push_back(d);
    chunk.push_back(std::max<hsize_t>(d, 1));
  }
  const int rank = static_cast<int>(dims.size());
  const hid_t space = H5Screate_simple(rank, dims.data(), maxdims.data());
  const hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
  H5Pset_chunk(dcpl, rank, chunk.data());
  // Rows arrive in whole blocks, so no chunk cache is needed; HDF5's default
  // (1 MB per dataset) would hold ~1 MB per channel for nothing.
  const hid_t dapl = H5Pcreate(H5P_DATASET_ACCESS);
  H5Pset_chunk_cache(dapl, H5D_CHUNK_CACHE_NSLOTS_DEFAULT, 0, H5D_CHUNK_CACHE_W0_DEFAULT);
  const hid_t d = H5Dcreate2(f.id(), path.c_str(), H5T_IEEE_F64LE, space, H5P_DEFAULT, dcpl, dapl);
  H5Pclose(dapl);
  H5Pclose(dcpl);
  H5Sclose(space);
  if (d < 0) throw OutputError(f.path() + ": cannot create " + path + fc::hdf5ErrorReason());
  return d;
}

void appendRows(hid_t d, const Channel& c, const std::string& file, unsigned long long at,
                unsigned long long rows, const double* data) {
  std::vector<hsize_t> size{static_cast<hsize_t>(at + rows)}, start{static_cast<hsize_t>(at)},
      count{static_cast<hsize_t>(rows)};
  const std::vector<hsize_t> trailing = !c.dims.empty() ? c.dims
                                        : c.rank1      ? std::vector<hsize_t>{}
                                                       : std::vector<hsize_t>{static_cast<hsize_t>(c.columns)};
  for (hsize_t t : trailing) {
    size.push_back(t);
    start.push_back(0);
    count.push_back(t);
  }
  const int rank = static_cast<int>(size.size());
  bool ok = H5Dset_extent(d, size.data()) >= 0;
  if (ok) {
    const hid_t fspace = H5Dget_space(d);
    const hid_t mspace = H5Screate_simple(rank, count.data(), nullptr);
    ok = fspace >= 0 && mspace >= 0 &&
         H5Sselect_hyperslab(fspace, H5S_SELECT_SET, start.data(), nullptr, count.data(), nullptr) >= 0 &&
         H5Dwrite(d, H5T_NATIVE_DOUBLE, mspace, fspace, H5P_DEFAULT, data) >= 0;
    // Read the reason before H5Sclose: every HDF5 call clears the error stack, and a
    // full disk was reported as "cannot write /bodies/p/ply_stress" without its errno.
    const std::string reason = ok ? std::string() : fc::hdf5ErrorReason();
    if (mspace >= 0) H5Sclose(mspace);
    if (fspace >= 0) H5Sclose(fspace);
    if (!ok) throw OutputError(file + ": cannot write /" + c.name + reason);
  }
  if (!ok) throw OutputError(file + ": cannot write /" + c.name + fc::hdf5ErrorReason());
}

}  // namespace

ResultsFileWriter::ResultsFileWriter(const std::string& path, const Model& model, long expected_rows)
    : channels_(resultChannels(model)), file_(path) {
  unsigned long long width = 0;
  for (const Channel& c : channels_) width += c.columns;
  block_rows_ = std::max(16ull, kBlockBytes / (8 * std::max(1ull, width)));
  // Chunks no longer than the run, so that a short run's file stays small.
  const unsigned long long chunk = std::max(1ull, std::min(block_rows_, static_cast<unsigned long long>(
                                                                            std::max(1l, expected_rows))));
  // The chunk indexes grow with the rows; HDF5's metadata cache (up to 32 MB
  // by default) is capped so that memory stays bounded whatever the output step.
  H5AC_cache_config_t mdc;
  mdc.version = H5AC__CURR_CACHE_CONFIG_VERSION;
  if (H5Fget_mdc_config(file_.file().id(), &mdc) >= 0) {
    mdc.set_initial_size = true;
    mdc.initial_size = 1 << 20;
    mdc.min_size = 1 << 20;
    mdc.max_size = 4 << 20;
    H5Fset_mdc_config(file_.file().id(), &mdc);
  }
  every_ = static_cast<unsigned long long>(std::max(1, model.stress_every));
  for (const Channel& c : channels_) {
    datasets_.push_back(createExtendible(file_.file(), c, chunk));
    buffers_.emplace_back();
    buffers_.back().reserve((c.decimated ? block_rows_ / every_ + 1 : block_rows_) * c.columns);
  }
  channel_rows_.assign(channels_.size(), 0);
  skipped_.resize(channels_.size());
  last_flush_ = std::chrono::steady_clock::now();
}

ResultsFileWriter::~ResultsFileWriter() {
  for (hid_t d : datasets_)
    if (d >= 0) H5Dclose(d);
}

void ResultsFileWriter::write(const Sample& s) {
  const bool keep = (written_ + buffered_) % every_ == 0;  // this row's index, 0-based
  for (std::size_t k = 0; k < channels_.size(); ++k) {
    if (channels_[k].decimated && !keep) {
      skipped_[k].resize(channels_[k].columns);
      channels_[k].read(s, skipped_[k].data());
      continue;
    }
    std::vector<double>& b = buffers_[k];
    b.resize(b.size() + channels_[k].columns);
    channels_[k].read(s, b.data() + b.size() - channels_[k].columns);
  }
  skipped_pending_ = !keep;
  ++buffered_;
  const bool due = std::chrono::duration<double>(std::chrono::steady_clock::now() - last_flush_).count() >
                   kFlushSeconds;
  if (buffered_ >= block_rows_ || due) writeBlock();
}

void ResultsFileWriter::writeBlock() {
  // Each channel its own rows: the decimated ones fewer (none in most blocks).
  for (std::size_t k = 0; k < channels_.size(); ++k) {
    const unsigned long long rows = buffers_[k].size() / static_cast<unsigned long long>(channels_[k].columns);
    if (rows > 0)
      appendRows(datasets_[k], channels_[k], file_.temporaryPath(), channel_rows_[k], rows, buffers_[k].data());
    channel_rows_[k] += rows;
    buffers_[k].clear();
  }
  written_ += buffered_;
  buffered_ = 0;
  // What is on disk is a valid HDF5 file up to here (HDF5 1.10 has no
  // single-writer journal: a flush is the consistency point).
  if (H5Fflush(file_.file().id(), H5F_SCOPE_GLOBAL) < 0)
    throw OutputError(file_.temporaryPath() + ": cannot flush" + fc::hdf5ErrorReason());
  last_flush_ = std::chrono::steady_clock::now();
}

void ResultsFileWriter::finish(const Model& model, const RunSummary& r, const std::string& inputs_sha256) {
  // The final row always goes to the decimated fields too (the state the run ended in).
  if (skipped_pending_) {
    for (std::size_t k = 0; k < channels_.size(); ++k)
      if (channels_[k].decimated) buffers_[k].insert(buffers_[k].end(), skipped_[k].begin(), skipped_[k].end());
    skipped_pending_ = false;
  }
  writeBlock();
  for (hid_t& d : datasets_) {
    if (H5Dclose(d) < 0) throw OutputError(file_.temporaryPath() + ": cannot close a dataset" + fc::hdf5ErrorReason());
    d = -1;
  }
  fc::H5File& f = file_.file();
  fc::writeProvenance(f, "results/1", "mbs-run", inputs_sha256);
  // The run's summaries, each a stage of its own (run_summary.h folds them).
  writeImpactsAndModalPeaks(f, model, r);
  writeStressFields(f, model, r);
  writeMargins(f, model, r);
  writeContactPeaks(f, model, r);
  writeRunAttributes(f, model, r);
  try {
    file_.commit();
  } catch (const std::exception& e) {
    throw OutputError(e.what());
  }
}

CsvWriter::CsvWriter(const std::string& path, const Model& model, const std::vector<std::string>& wanted)
    : path_(path) {
  const std::vector<Channel> all = resultChannels(model);
  chosen_.push_back(all[0]);
  for (const std::string& w : wanted) {
    auto hit = std::find_if(all.begin(), all.end(), [&](const Channel& c) { return c.name == w; });
    if (hit == all.end()) {
      std::string list;
      for (const Channel& c : all) list += " " + c.name;
      throw std::invalid_argument("--channels: unknown channel '" + w + "'; available:" + list);
    }
    if (hit != all.begin()) chosen_.push_back(*hit);
  }
  for (int attempt = 0; fd_ < 0; ++attempt) {
    tmp_path_ = fc::temporaryNameFor(path);
    fd_ = ::open(tmp_path_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
    if (fd_ < 0 && (errno != EEXIST || attempt >= 8))
      throw std::runtime_error("cannot create a temporary file beside " + path + ": " + tmp_path_ + ": " +
                               fc::osReason(errno));
  }
  registration_ = std::make_unique<fc::TemporaryRegistration>(tmp_path_);
  const char* xyz[] = {"x", "y", "z", "w"};
  std::ostringstream s;
  for (std::size_t k = 0; k < chosen_.size(); ++k) {
    const Channel& c = chosen_[k];
    for (int i = 0; i < c.columns; ++i) {
      if (k || i) s << ",";
      s << c.name;
      if (c.name.find("/modal_") != std::string::npos || !c.dims.empty()) s << "_" << i + 1;
      else if (c.columns == 4) s << "_e" << i;
      else if (c.columns > 1) s << "_" << xyz[i];
    }
  }
  buffer_ = s.str() + "\n";
}

CsvWriter::~CsvWriter() {
  if (fd_ >= 0) {
    ::close(fd_);
    ::unlink(tmp_path_.c_str());
  }
}

void CsvWriter::write(const Sample& sample) {
  std::ostringstream s;
  s << std::setprecision(12);
  std::vector<double> row;
  for (std::size_t k = 0; k < chosen_.size(); ++k) {
    row.resize(chosen_[k].columns);
    chosen_[k].read(sample, row.data());
    for (std::size_t i = 0; i < row.size(); ++i) {
      if (k || i) s << ",";
      s << row[i];
    }
  }
  buffer_ += s.str() + "\n";
  if (buffer_.size() >= kBlockBytes) drain();
}

void CsvWriter::drain() {
  const char* p = buffer_.data();
  std::size_t n = buffer_.size();
  while (n > 0) {
    const ssize_t w = ::write(fd_, p, n);
    if (w < 0 && errno == EINTR) continue;
    if (w <= 0) throw OutputError("cannot write " + tmp_path_ + ": " + fc::osReason(errno));
    p += w;
    n -= static_cast<std::size_t>(w);
  }
  buffer_.clear();
}

void CsvWriter::finish() {
  drain();
  if (::fsync(fd_) != 0) throw OutputError("cannot write " + tmp_path_ + ": " + fc::osReason(errno));
  const int rc = ::close(fd_);
  fd_ = -1;
  if (rc != 0 || std::rename(tmp_path_.c_str(), path_.c_str()) != 0) {
    const int err = errno;
    ::unlink(tmp_path_.c_str());
    throw OutputError("cannot write " + path_ + ": " + fc::osReason(err));
  }
  registration_.reset();
  fc::fsyncDirectoryOf(path_);
}

void writeResults(const std::string& path, const Model& model, const Results& r, const std::string& inputs_sha256) {
  ResultsFileWriter w(path, model, static_cast<long>(r.time.size()));
  for (std::size_t i = 0; i < r.time.size(); ++i) w.write(r.row(i));
  w.finish(model, r, inputs_sha256);
}

void writeCsv(const std::string& path, const Model& model, const Results& r, const std::vector<std::string>& channels) {
  CsvWriter w(path, model, channels);
  for (std::size_t i = 0; i < r.time.size(); ++i) w.write(r.row(i));
  w.finish();
}

}  // namespace fc::mbs
