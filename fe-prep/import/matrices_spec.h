#pragma once
// body.matrices of a body YAML (contracts.md, "General bodies"): where another
// FE code's matrices, DOF list and nodes are, and in what units.
#include <string>
#include <vector>

#include "common/input.h"
#include "common/units.h"

namespace fc::feprep {

struct MatricesSpec {
  std::string format;                 // calculix | abaqus | matrix_market
  std::string stiffness, mass, dofs;  // dofs empty: from the files (abaqus five-column form)
  std::string model;                  // node table: .inp (*NODE, *NSET, *ELEMENT) or "label x y z"
  std::string reference_frequencies;  // optional: CalculiX .dat of *FREQUENCY on the same free model
  UnitSystem units;                   // the files' units (body.units, required)
  InputNode node;                     // the matrices: map, for errors found later
};

// Parses body.matrices (and body.units); the files it names are appended to
// `files` (for the inputs' SHA-256). InputError on a missing or unknown key.
MatricesSpec parseMatricesSpec(const InputNode& body, std::vector<std::string>& files);

}  // namespace fc::feprep
