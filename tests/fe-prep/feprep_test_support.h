#pragma once
// Shared by the fe-prep tests: SLEPc/PETSc set up once per test program, and
// running the whole tool path (YAML -> gmsh -> PETSc/SLEPc -> FlexBody) on a
// YAML string.
#include <gtest/gtest.h>
#include <mpi.h>

#include <string>

#include "fe-prep/body_spec.h"
#include "fe-prep/build_body.h"

namespace fc::feprep::test {

// Runs fe-prep's pipeline on YAML text (errors name "<test>" as the file).
BuildResult runYaml(const std::string& yaml, const std::string& name = "<test>");

// Path of the built fe-prep executable and a fresh scratch directory.
std::string feprepExecutable();
std::string scratchDir(const std::string& test_name);

}  // namespace fc::feprep::test
