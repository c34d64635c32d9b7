#pragma once
// Reading a scene file (contracts.md, "mbs-run", plus the extensions in
// docs/mbs-run.md) into a Model. Every error is an fc::InputError naming the
// file, line, key, what is wrong and what is expected.
#include <optional>
#include <string>

#include "common/input.h"
#include "mbs-run/model/model.h"

namespace fc::mbs {

Model loadScene(const std::string& path);
Model parseScene(const fc::InputNode& root);

// Which integrator IntegratorKind::Auto means for this model: TR-BDF2 when a
// force element's natural frequency would force an explicit method to steps
// far below the output step, Dormand-Prince otherwise.
IntegratorKind chooseIntegrator(const Model& model);

// The integrator a name asks for (`auto`, `dopri5`, `trbdf2`, `imex`: the
// scene's simulation.integrator and mbs-run's --integrator), none if unknown.
std::optional<IntegratorKind> integratorNamed(const std::string& name);
// The one place `auto` is decided: an Auto integrator becomes
// chooseIntegrator's, and switches to an implicit method when stiff
// (Settings::switch_when_stiff) only when that is Dormand-Prince; a named
// method runs throughout.
void resolveAutoIntegrator(Model& model);

}  // namespace fc::mbs
