#include "fe-prep/import/matrices_spec.h"

#include <fstream>
#include <stdexcept>

#include "common/files.h"

namespace fc::feprep {

MatricesSpec parseMatricesSpec(const InputNode& body, std::vector<std::string>& files) {
  const InputNode m = body["matrices"];
  MatricesSpec spec;
  spec.node = m;
  m.allowKeys({"format", "stiffness", "mass", "dofs", "model", "reference_frequencies"});
  spec.format = m["format"].asString();
  if (spec.format != "calculix" && spec.format != "abaqus" && spec.format != "matrix_market")
    m["format"].fail("unknown format '" + spec.format + "', expected calculix, abaqus or matrix_market");
  auto path = [&](const char* key) {
    const std::string p = resolveRelativeTo(m.file(), m[key].asString());
    if (!std::ifstream(p)) m[key].fail("cannot read '" + p + "'");
    files.push_back(p);
    return p;
  };
  spec.stiffness = path("stiffness");
  spec.mass = path("mass");
  if (m.has("dofs")) spec.dofs = path("dofs");
  else if (spec.format != "abaqus")
    m.fail("missing dofs: the " + spec.format + " matrices need a file naming each row's node and DOF" +
           (spec.format == "calculix" ? " (CalculiX writes JOB.dof)" : " (\"node dof\" lines)"));
  spec.model = path("model");
  if (m.has("reference_frequencies")) spec.reference_frequencies = path("reference_frequencies");
  // The matrices carry no units: a missing units: would silently read a mm model as metres.
  if (!body.has("units"))
    body.fail("missing units: imported matrices carry none; give the source model's system, e.g. units: mm-t-s "
              "(mm, tonne, s: N, MPa) or units: m-kg-s");
  try {
    spec.units = unitSystem(body["units"].asString());
  } catch (const std::invalid_argument& e) {
    body["units"].fail(e.what());
  }
  return spec;
}

}  // namespace fc::feprep
