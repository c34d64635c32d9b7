// mbs-run SCENE.yaml -o RESULTS.h5: multibody dynamics of a scene.
#include <algorithm>
#include <CLI/CLI.hpp>
#include <cstdio>
#include <fstream>
#include <memory>
#include <optional>
#include <set>
#include <sstream>

#include "common/cli.h"
#include "common/inspect.h"
#include "common/files.h"
#include "common/memory.h"
#include "common/termination.h"
#include "common/version.h"
#include "mbs-run/output/animation.h"
#include "mbs-run/mechanics/constraints.h"
#include "mbs-run/mechanics/flexible/flexible_body.h"
#include "mbs-run/monitors/stress_recovery.h"
#include "mbs-run/output/results.h"
#include "mbs-run/scene/scene.h"
#include "mbs-run/run/run_policy.h"
#include "mbs-run/run/simulation.h"

namespace {

std::vector<std::string> splitComma(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, ','))
    if (!item.empty()) out.push_back(item);
  return out;
}

// Hands each row to every writer.
class Fanout : public fc::mbs::SampleSink {
 public:
  explicit Fanout(std::vector<fc::mbs::SampleSink*> sinks) : sinks_(std::move(sinks)) {}
  void write(const fc::mbs::Sample& s) override {
    for (fc::mbs::SampleSink* k : sinks_)
      if (k) k->write(s);
  }

 private:
  std::vector<fc::mbs::SampleSink*> sinks_;
};

void printPeak(const char* what, const fc::mbs::RunSummary::Peak& p, const char* unit) {
  if (p.where.empty() && p.value == 0.0) return;
  std::printf("  largest %s %.4g %s (%s, t = %.6g s)\n", what, p.value, unit, p.where.c_str(), p.time);
}

// --seen-warnings: the warnings a set of runs has already shown, one per line.
std::set<std::string> readSeenWarnings(const std::string& path) {
  std::set<std::string> seen;
  if (path.empty()) return seen;
  std::ifstream in(path);
  for (std::string line; std::getline(in, line);)
    if (!line.empty()) seen.insert(line);
  return seen;
}
void addSeenWarnings(const std::string& path, const std::set<std::string>& seen, const std::vector<std::string>& now) {
  if (path.empty()) return;
  std::ofstream out(path, std::ios::app);  // a log of what was shown, not a result: appended, not atomic
  for (const std::string& w : now)
    if (!seen.count(w)) out << w << "\n";
}

// The run: what was modelled, how the integrator did, the balance of energy and the peak reactions.
void printRunFigures(const fc::mbs::Model& m, const fc::mbs::RunSummary& r, const std::string& out) {
  const double t = r.t_reached;
  std::printf("mbs-run %s: %s -> %s\n", fc::version(), m.source.c_str(), out.c_str());
  std::printf("  status: %s (t = %.6g of %.6g s)\n", r.status.c_str(), t, m.settings.t_end);
  // What was modelled: only what the scene asks for (rigid bodies read no file,
  // flexible ones only their first `modes` modes).
  int n_flexible = 0, n_modes = 0, n_fixed = 0, n_rows = 0;
  for (const auto& b : m.bodies) {
    n_fixed += b.fixed ? 1 : 0;
    n_flexible += b.modes > 0 ? 1 : 0;
    n_modes += b.modes;
  }
  for (const auto& jt : m.joints) {
    fc::mbs::JointRuntime rt;
    rt.enabled = jt.enabled;
    rt.locked = jt.locked;
    n_rows += fc::mbs::constraintCount(jt, rt);
  }
  std::printf("  model: %zu bodies (%d fixed, %d flexible with %d modes in all), %d position / %d velocity "
              "coordinates, %zu joints with %d constraint equations at t = 0\n",
              m.bodies.size(), n_fixed, n_flexible, n_modes, m.nq, m.nv, m.joints.size(), n_rows);
  std::printf("  formulation: %s\n", r.formulation.c_str());
  std::printf("  integrator %s, rtol %.3g: %ld steps, %ld rejected, %ld evaluations, %ld projections, "
              "AL iterations <= %d\n",
              r.integrator.c_str(), m.settings.rtol, r.steps, r.rejected_steps, r.evaluations, r.projections,
              r.max_al_iterations);
  std::printf("  CPU %.3f s, real-time factor %.3g (simulated s per CPU s), %ld output rows\n", r.cpu_seconds,
              r.cpu_seconds > 0 ? t / r.cpu_seconds : 0.0, r.samples);
  std::printf("  largest constraint violation %.3e (t = %.6g s)\n", r.max_violation, r.peak_violation.time);
  std::printf("  energy balance error %.3e J (%.3e of the largest energy term %.3e J)\n", r.energy_balance_error,
              r.energy_scale > 0 ? r.energy_balance_error / r.energy_scale : 0.0, r.energy_scale);
  printPeak("reaction force", r.peak_reaction_force, "N");
  printPeak("reaction torque", r.peak_reaction_torque, "N m");
  printPeak("modal coordinate", r.peak_modal_coordinate, "kg^1/2 m");
}

// Which modes the run excited: the highest kept modes' share, the fixed-interface modes by energy.
void printModalEnergy(const fc::mbs::Model& m, const fc::mbs::RunSummary& r) {
  for (std::size_t k = 0; k < m.bodies.size() && k < r.peak_modal_energy.size(); ++k) {
    const Eigen::VectorXd& e = r.peak_modal_energy[k];
    if (e.size() == 0) continue;
    int top = 0;
    const double share = fc::mbs::highestModesEnergyShare(e, &top);
    Eigen::Index biggest = 0;
    e.maxCoeff(&biggest);
    std::printf("  modal energy %s: the highest %d of %ld modes carry %.3g %% of the summed per-mode peaks "
                "(%.4g J); mode %ld peaks highest (%.4g J)%s\n",
                m.bodies[k].name.c_str(), top, static_cast<long>(e.size()), 100 * share, e.sum(),
                static_cast<long>(biggest) + 1, e(biggest),
                share > 0.05 ? ": the highest kept modes are excited, try more modes" : "");
  }
  for (std::size_t k = 0; k < m.bodies.size() && k < r.peak_fixed_interface_energy.size(); ++k) {
    const Eigen::VectorXd& e = r.peak_fixed_interface_energy[k];
    if (e.size() == 0) continue;
    const fc::mbs::ModeRanking rank = fc::mbs::rankByPeakEnergy(e, m.bodies[k].flex->fixed_interface_modes);
    std::string list;
    for (std::size_t i = 0; i < rank.modes.size() && i < 12; ++i) {
      char buf[48];
      std::snprintf(buf, sizeof buf, "%s%ld (%.3g %%)", i ? ", " : "", rank.modes[i], 100 * rank.share[i]);
      list += buf;
    }
    std::printf("  fixed-interface modes %s by peak strain energy: %s%s (a body YAML's modes: {keep: [...]} "
                "can keep the most excited)\n",
                m.bodies[k].name.c_str(), list.c_str(), rank.modes.size() > 12 ? ", ..." : "");
  }
}

// Stresses, warnings, events, distances and contacts.
void printPeaks(const fc::mbs::Model& m, const fc::mbs::RunSummary& r, const std::set<std::string>& seen_warnings) {
  if (r.peak_failure_index.found)
    std::printf("  largest Tsai-Wu failure index %.4g (body %s, element %ld, ply %ld, 0-based; t = %.6g s)%s\n",
                r.peak_failure_index.value, r.peak_failure_index.body.c_str(), r.peak_failure_index.element,
                r.peak_failure_index.ply, r.peak_failure_index.time,
                r.peak_failure_index.value >= 1.0 ? ": FAILURE (index >= 1)" : "");
  if (r.peak_section_moment.found)
    std::printf("  largest beam section bending moment %.4g N m (body %s, element %ld, 0-based; t = %.6g s)\n",
                r.peak_section_moment.value, r.peak_section_moment.body.c_str(), r.peak_section_moment.element,
                r.peak_section_moment.time);
  for (const std::string& w : r.warnings)
    if (!seen_warnings.count(w)) std::printf("  warning: %s\n", w.c_str());
  for (const std::string& e : r.event_log) std::printf("  event %s\n", e.c_str());
  for (std::size_t k = 0; k < m.distance_pairs.size() && k < r.smallest_distance.size(); ++k)
    std::printf("  distance %s-%s: smallest %.4g m at t = %.6g s\n", m.bodies[m.distance_pairs[k][0]].name.c_str(),
                m.bodies[m.distance_pairs[k][1]].name.c_str(), r.smallest_distance[k].value,
                r.smallest_distance[k].time);
  {
    const std::vector<int> contacts = m.contactElements();
    for (std::size_t k = 0; k < contacts.size() && k < r.peak_contact_force.size(); ++k)
      std::printf("  contact %s: largest force %.4g N at t = %.6g s, largest penetration %.4g m at t = %.6g s\n",
                  m.forces[static_cast<std::size_t>(contacts[k])].name.c_str(), r.peak_contact_force[k].value,
                  r.peak_contact_force[k].time, r.peak_contact_penetration[k].value, r.peak_contact_penetration[k].time);
  }
}

void printMargins(const fc::mbs::Model& m, const fc::mbs::RunSummary& r) {
  // Margins (run/margins.h): the named beams against buckling, the named
  // joints' peak reactions, every latch's arrival.
  const fc::mbs::Margins& mg = r.margins;
  for (std::size_t k = 0; k < m.margin_beams.size() && k < mg.beams.size(); ++k) {
    const fc::mbs::BeamMarginSpec& b = m.margin_beams[k];
    const double ratio = mg.beams[k].compression / b.euler_load;
    std::printf("  margin %s: largest compression %.4g N at t = %.6g s, %.3g of its Euler load %.4g N (EI %.4g N m^2, "
                "L %.4g m, %s ends, K %.3g); largest tension %.4g N at t = %.6g s%s\n",
                m.bodies[b.body].name.c_str(), mg.beams[k].compression, mg.beams[k].compression_time, ratio,
                b.euler_load, b.EI, b.length, b.ends.c_str(), b.K, mg.beams[k].tension, mg.beams[k].tension_time,
                ratio >= 1.0 ? ": ABOVE THE EULER LOAD" : "");
  }
  for (int j : m.margin_joints) {
    if (static_cast<std::size_t>(j) >= mg.joints.size()) continue;
    const auto& p = mg.joints[static_cast<std::size_t>(j)];
    if (m.joints[j].type == fc::mbs::JointType::Spherical)
      std::printf("  margin joint %s: peak reaction force %.4g N at t = %.6g s\n", m.joints[j].name.c_str(), p.force,
                  p.force_time);
    else
      std::printf("  margin joint %s: peak reaction force %.4g N at t = %.6g s, moment %.4g N m at t = %.6g s\n",
                  m.joints[j].name.c_str(), p.force, p.force_time, p.moment, p.moment_time);
  }
  for (std::size_t k = 0; k < r.body_failure_peaks.size() && k < m.bodies.size(); ++k) {
    const auto& p = r.body_failure_peaks[k];
    if (!p.found) continue;
    const bool beam = m.bodies[k].stress && m.bodies[k].stress->kind == fc::mbs::BodyStressRecovery::Kind::Beam;
    std::printf("  margin failure index %s: peak %.4g at t = %.6g s (%s %ld, %s %ld, 0-based)%s\n", p.body.c_str(), p.value,
                p.time, beam ? "station" : "element", p.element, beam ? "section element" : "ply", p.ply,
                p.value >= 1.0 ? ": FAILURE (index >= 1)" : "");
  }
  for (const auto& l : mg.latches)
    std::printf("  latch %s: at t = %.10g s (angle %.6g rad), arriving at %.4g rad/s\n", m.joints[l.joint].name.c_str(),
                l.time, l.angle, l.rate);
  {
    // One line: the joint that went furthest past a stop or latch (each
    // joint's own figure and angle range are attributes of its angle).
    int worst = -1;
    const double largest = mg.largestOvershoot(m, &worst);
    if (worst >= 0)
      std::printf("  largest overshoot past a stop or latch %.3g rad (joint %s, angle from %.6g to %.6g rad)\n", largest,
                  m.joints[worst].name.c_str(), mg.joints[worst].angle_min, mg.joints[worst].angle_max);
  }
}

void printSummary(const fc::mbs::Model& m, const fc::mbs::RunSummary& r, const std::string& out,
                  const std::set<std::string>& seen_warnings) {
  printRunFigures(m, r, out);
  printModalEnergy(m, r);
  printPeaks(m, r, seen_warnings);
  printMargins(m, r);
  if (r.samples > 0 && r.energy_dissipated != 0.0)
    std::printf("  energy dissipated %.6g J (damping, friction, impacts)\n", r.energy_dissipated);
  for (const std::string& e : r.integrator_log) std::printf("  integrator %s\n", e.c_str());
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"mbs-run: multibody dynamics of rigid (and flexible) bodies with joints, actuators and events"};
  std::string input, output, csv, channels;
  double t_end = -1, rtol = -1;
  std::string integrator, animation;
  int animation_every = 1;
  bool quiet = false, accept_inaccurate = false;
  app.add_option("scene", input, "scene YAML file (keys: see the input reference below)")->required();
  app.add_option("-o,--output", output, "results file to write (HDF5, results/1)")->required();
  app.add_option("--t-end", t_end, "end time, overrides simulation.t_end")->check(CLI::PositiveNumber);
  app.add_option("--rtol", rtol, "relative tolerance, overrides simulation.rtol")->check(CLI::Range(1e-13, 0.1));
  std::string names;
  for (const std::string& n : fc::mbs::integratorNames()) names += (names.empty() ? "" : " | ") + n;
  app.add_option("--integrator", integrator, names + ", overrides simulation.integrator")
      ->check(CLI::IsMember(fc::mbs::integratorNames()));
  app.add_option("--csv", csv, "also write chosen channels to this CSV file");
  app.add_option("--channels", channels,
                 "comma-separated channels for --csv, e.g. joints/R3/angle,bodies/B3/angular_velocity "
                 "(default: revolute angles and energies)");
  app.add_option("--animation", animation,
                 "also write a ParaView animation R.pvd (and the folder R/) from the results file after the run")
      ->check([](const std::string& p) {
        return p.size() > 4 && p.compare(p.size() - 4, 4, ".pvd") == 0 ? "" : "expected a file name ending in .pvd";
      });
  app.add_option("--animation-every", animation_every, "write every N-th output time to the animation")
      ->check(CLI::PositiveNumber);
  app.add_flag("-q,--quiet", quiet, "no progress on stderr");
  std::string seen_warnings;
  app.add_option("--seen-warnings", seen_warnings,
                 "a text file of warnings already shown (one per line): print only the others and add them to it, so "
                 "a set of runs (a Makefile) shows each warning once; the results file keeps every warning");
  app.add_flag("--accept-inaccurate", accept_inaccurate,
               "exit 0 when the run ends with status 'inaccurate' (energy balance or constraint drift beyond what "
               "its tolerances allow; the results are written either way)");
  app.set_version_flag("--version", std::string("mbs-run ") + fc::version());
  fc::addInspectOption(app, "mbs-run", fc::inspectFile);
  fc::addInputReferenceFooter(app);
  CLI11_PARSE(app, argc, argv);

  return fc::guardedMain("mbs-run", [&] {
    // A termination signal (INT, TERM, HUP, QUIT, ALRM, XCPU, PIPE) is only
    // recorded: the loop stops at the next step and the file is finished with
    // status "interrupted by SIGxxx"; a second one exits at once.
    fc::installTerminationHandlers("mbs-run", fc::TerminationPolicy::Record);
    // Each stage is named for an out-of-memory message (common/memory.h).
    std::optional<fc::StageScope> stage(std::in_place, "reading the scene");
    fc::mbs::Model model = fc::mbs::loadScene(input);
    if (t_end > 0) model.settings.t_end = t_end;
    if (rtol > 0) model.settings.rtol = rtol;
    // --integrator replaces the scene's choice; the run decides what it means (run/run_policy.h).
    if (!integrator.empty()) model.settings.integrator = *fc::mbs::integratorNamed(integrator);
    std::vector<std::string> chosen = splitComma(channels);
    if (chosen.empty()) {
      for (const auto& j : model.joints)
        if (j.type == fc::mbs::JointType::Revolute) chosen.push_back("joints/" + j.name + "/angle");
      for (const char* e : {"energy/kinetic", "energy/potential", "energy/dissipated"}) chosen.push_back(e);
    }
    // Before any computing: the outputs must not destroy an input (the scene,
    // an included file, a body file) and must be writable.
    for (const std::string& out : {output, csv}) {
      if (out.empty()) continue;
      fc::checkOutputIsNotAnInput(out, fc::inputFilesRead());
      fc::checkOutputWritable(out);
    }
    if (!csv.empty()) fc::checkOutputIsNotAnInput(csv, {output});
    if (!animation.empty()) fc::mbs::prepareAnimationFolder(animation);  // fail before the run, not after
    const std::set<std::string> seen = readSeenWarnings(seen_warnings);
    for (const std::string& w : fc::mbs::samplingWarnings(model))
      if (!seen.count(w)) std::fprintf(stderr, "mbs-run: warning: %s\n", w.c_str());
    const long expected_rows = static_cast<long>(model.settings.t_end / model.settings.output_step) + 2;
    stage.emplace("integration");
    fc::mbs::ResultsFileWriter file(output, model, expected_rows);
    std::unique_ptr<fc::mbs::CsvWriter> table;
    if (!csv.empty()) table = std::make_unique<fc::mbs::CsvWriter>(csv, model, chosen);
    Fanout sinks({&file, table.get()});
    fc::mbs::RunOptions opt;
    opt.quiet = quiet;
    const fc::mbs::RunSummary r = fc::mbs::simulate(model, opt, sinks);
    stage.emplace("writing " + output);
    file.finish(model, r, fc::sha256File(input));
    if (table) table->finish();
    printSummary(model, r, output, seen);
    addSeenWarnings(seen_warnings, seen, r.warnings);
    if (!animation.empty()) {
      stage.emplace("writing the animation " + animation);
      const fc::mbs::AnimationSummary a = fc::mbs::writeAnimation(animation, input, model, output, animation_every);
      std::printf("  animation %s: %d frames of %d bodies (files in %s)\n", animation.c_str(), a.frames, a.bodies,
                  a.folder.c_str());
    }
    std::fflush(stdout);
    // Exit codes: 0 completed, 4 inaccurate (unless accepted), a signal's
    // own code when interrupted, 3 otherwise stopped early.
    if (r.status == "completed") return 0;
    if (r.status.rfind("inaccurate", 0) == 0) return accept_inaccurate ? 0 : 4;
    if (const int sig = fc::terminationSignal()) return fc::terminationExitCode(sig);
    return 3;
  });
}
