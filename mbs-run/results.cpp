#include "mbs-run/results.h"

#include <algorithm>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <stdexcept>

#include "common/files.h"
#include "common/h5io.h"

namespace fc::mbs {

namespace {

template <int N>
Eigen::MatrixXd rows(const std::vector<Eigen::Matrix<double, N, 1>>& v) {
  Eigen::MatrixXd m(v.size(), N);
  for (std::size_t k = 0; k < v.size(); ++k) m.row(k) = v[k].transpose();
  return m;
}

Eigen::VectorXd column(const std::vector<double>& v) {
  return Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size()));
}

std::string distanceChannel(const Model& m, std::size_t k) {
  return "distances/" + m.bodies[m.distance_pairs[k][0]].name + "-" + m.bodies[m.distance_pairs[k][1]].name;
}

// Every channel by name, as an (n_out, k) matrix.
std::vector<std::pair<std::string, Eigen::MatrixXd>> channels(const Model& m, const Results& r) {
  std::vector<std::pair<std::string, Eigen::MatrixXd>> c;
  c.emplace_back("time", column(r.time));
  for (std::size_t k = 0; k < m.bodies.size(); ++k) {
    const std::string b = "bodies/" + m.bodies[k].name + "/";
    c.emplace_back(b + "position", rows<3>(r.position[k]));
    c.emplace_back(b + "orientation", rows<4>(r.orientation[k]));
    c.emplace_back(b + "velocity", rows<3>(r.velocity[k]));
    c.emplace_back(b + "angular_velocity", rows<3>(r.angular_velocity[k]));
    const int nm = m.bodies[k].modes;
    if (nm > 0) {
      Eigen::MatrixXd q(r.modal[k].size(), nm), qd(r.modal[k].size(), nm);
      for (std::size_t i = 0; i < r.modal[k].size(); ++i) {
        q.row(i) = r.modal[k][i].transpose();
        qd.row(i) = r.modal_rate[k][i].transpose();
      }
      c.emplace_back(b + "modal_coordinates", q);
      c.emplace_back(b + "modal_velocities", qd);
    }
  }
  for (std::size_t j = 0; j < m.joints.size(); ++j) {
    const std::string p = "joints/" + m.joints[j].name + "/";
    if (m.joints[j].type == JointType::Revolute) c.emplace_back(p + "angle", column(r.joint_angle[j]));
    c.emplace_back(p + "reaction_force", rows<3>(r.reaction[j]));
    if (m.joints[j].limits.any() && j < r.limit_state.size()) {
      c.emplace_back(p + "limit_state", column(std::vector<double>(r.limit_state[j].begin(), r.limit_state[j].end())));
      c.emplace_back(p + "limit_torque", column(r.limit_torque[j]));
    }
  }
  for (std::size_t k = 0; k < m.distance_pairs.size() && k < r.distances.size(); ++k)
    c.emplace_back(distanceChannel(m, k), column(r.distances[k]));
  c.emplace_back("energy/kinetic", column(r.kinetic));
  c.emplace_back("energy/potential", column(r.potential));
  c.emplace_back("energy/strain", column(r.strain));
  c.emplace_back("energy/dissipated", column(r.dissipated));
  c.emplace_back("energy/applied_work", column(r.applied_work));
  c.emplace_back("diagnostics/constraint_violation", column(r.violation));
  return c;
}

}  // namespace

void writeResults(const std::string& path, const Model& model, const Results& r,
                  const std::string& inputs_sha256) {
  fc::AtomicH5Writer w(path);
  fc::H5File& f = w.file();
  fc::writeProvenance(f, "results/1", "mbs-run", inputs_sha256);
  for (const auto& [name, data] : channels(model, r)) {
    if (data.cols() == 1) f.writeVector("/" + name, data.col(0));
    else f.writeMatrix("/" + name, data);
  }
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
  // Contact monitor summary: the smallest distance of each pair and when.
  for (std::size_t k = 0; k < model.distance_pairs.size() && k < r.distances.size(); ++k) {
    const std::vector<double>& d = r.distances[k];
    if (d.empty()) continue;
    const std::size_t i = std::min_element(d.begin(), d.end()) - d.begin();
    f.setAttribute("/" + distanceChannel(model, k), "minimum", d[i]);
    f.setAttribute("/" + distanceChannel(model, k), "time_of_minimum", r.time[i]);
  }
  f.setAttribute("/", "cpu_seconds", r.cpu_seconds);
  f.setAttribute("/", "steps", r.steps);
  f.setAttribute("/", "rejected_steps", r.rejected_steps);
  f.setAttribute("/", "status", r.status);
  f.setAttribute("/", "integrator", r.integrator);
  // The tolerances actually used (scene, preset or --rtol), for studies that
  // compare runs.
  f.setAttribute("/", "rtol", model.settings.rtol);
  f.setAttribute("/", "atol", model.settings.atol > 0 ? model.settings.atol : 1e-3 * model.settings.rtol);
  f.setAttribute("/", "t_reached", r.t_reached);
  f.setAttribute("/", "max_constraint_violation", r.max_violation);
  f.setAttribute("/", "energy_balance_error", r.energy_balance_error);
  f.setAttribute("/", "rhs_evaluations", r.evaluations);
  std::string log;
  for (const std::string& e : r.event_log) log += e + "\n";
  f.setAttribute("/", "events", log);
  std::string switches;
  for (const std::string& e : r.integrator_log) switches += e + "\n";
  f.setAttribute("/", "integrator_switches", switches);
  w.commit();
}

void writeCsv(const std::string& path, const Model& model, const Results& r,
              const std::vector<std::string>& wanted) {
  const auto all = channels(model, r);
  std::vector<const std::pair<std::string, Eigen::MatrixXd>*> chosen{&all[0]};
  for (const std::string& w : wanted) {
    const std::pair<std::string, Eigen::MatrixXd>* hit = nullptr;
    for (const auto& c : all)
      if (c.first == w) hit = &c;
    if (!hit) {
      std::string list;
      for (const auto& c : all) list += " " + c.first;
      throw std::invalid_argument("--channels: unknown channel '" + w + "'; available:" + list);
    }
    if (hit != &all[0]) chosen.push_back(hit);
  }
  std::ostringstream s;
  s << std::setprecision(12);
  const char* xyz[] = {"x", "y", "z", "w"};
  for (std::size_t k = 0; k < chosen.size(); ++k) {
    const auto& [name, m] = *chosen[k];
    for (Eigen::Index c = 0; c < m.cols(); ++c) {
      if (k || c) s << ",";
      s << name;
      if (name.find("/modal_") != std::string::npos) s << "_" << c + 1;
      else if (m.cols() == 4) s << "_e" << c;
      else if (m.cols() > 1) s << "_" << xyz[c];
    }
  }
  s << "\n";
  for (std::size_t i = 0; i < r.time.size(); ++i) {
    for (std::size_t k = 0; k < chosen.size(); ++k) {
      const Eigen::MatrixXd& m = chosen[k]->second;
      for (Eigen::Index c = 0; c < m.cols(); ++c) {
        if (k || c) s << ",";
        s << m(static_cast<Eigen::Index>(i), c);
      }
    }
    s << "\n";
  }
  fc::writeFileAtomic(path, s.str());
}

}  // namespace fc::mbs
