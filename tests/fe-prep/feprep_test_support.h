#pragma once
// Shared by the fe-prep tests: SLEPc/PETSc set up once per test program, and
// running the whole tool path (YAML -> gmsh -> PETSc/SLEPc -> FlexBody) on a
// YAML string.
#include <gtest/gtest.h>
#include <mpi.h>

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

// Path of the built fe-prep executable and a fresh scratch directory.
std::string feprepExecutable();
std::string scratchDir(const std::string& test_name);

}  // namespace fc::feprep::test
