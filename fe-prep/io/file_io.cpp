// The functions of fe-prep's file table (file_io.h), on common/h5io.h.
#include "fe-prep/io/file_io.h"

#include "common/flexbody.h"
#include "common/h5io.h"
#include "common/inspect.h"

namespace fc::feprep {

namespace {

SectionFile readSection(const std::string& path, bool with_stress_basis) {
  SectionFile s;
  H5File f(path, H5File::Mode::Read);
  f.checkFormat("section", 1);
  s.stiffness = f.readMatrix("/stiffness/timoshenko", 6, 6);
  s.mass = f.readMatrix("/mass/matrix", 6, 6);
  if (with_stress_basis) s.stress_basis = readSectionStressBasis(path);
  return s;
}

}  // namespace

const FileIO& linkedFileIO() {
  static const FileIO io{&writeFlexBody, &readSection, &inspectFile};
  return io;
}

}  // namespace fc::feprep
