#pragma once
// Shared by the fe-prep tests: SLEPc/PETSc set up once per test program, and
// running the whole tool path (YAML -> gmsh -> PETSc/SLEPc -> FlexBody) on a
// YAML string.
#include <gtest/gtest.h>
#include <mpi.h>

#include <map>
#include <string>
#include <utility>
#include <vector>

#include "fe-prep/body_spec.h"
#include "fe-prep/build_body.h"

namespace fc::feprep::test {

// Runs fe-prep's pipeline on YAML text (errors name "<test>" as the file).
BuildResult runYaml(const std::string& yaml, const std::string& name = "<test>");

// Text of a body file under tests/data/fe-prep/ (a sweep's shared body), with
// the first "key: value" of each given key set to the given value (a plain
// scalar, inline or on its own line).
std::string dataBodyYaml(const std::string& name, const std::vector<std::pair<std::string, std::string>>& set = {});

// The steel cantilever of the static-error and residual-flexibility tests:
// L = 2 m, 40 beam elements, solid circle d = 0.02 m, clamped at interface
// `root` (x = -1), interface `tip` at the free end; `modes` is the value of
// its `modes:` key.
std::string steelCantileverYaml(const std::string& modes);

// The panel of tests/data/calculix/raised_pins_panel (CalculiX's decks): 1 x
// 0.65 m, 2 mm, hung at two hinge points H1, H2 70 mm above the mid-surface
// through distributing patches of radius 0.1 m, with a third raised point T
// at the far edge coupled by `t_coupling`; `modes` is the value of `modes:`.
std::string raisedPinsPanelYaml(const std::string& t_coupling, const std::string& modes);

// CalculiX's numbers for that panel (ccx_results.txt there): its
// "KEY NX v1 .. v6" lines keyed by "KEY NX".
std::map<std::string, std::vector<double>> raisedPinsPanelCalculix();

// Path of the built fe-prep executable and a fresh scratch directory.
std::string feprepExecutable();
std::string scratchDir(const std::string& test_name);

}  // namespace fc::feprep::test
