#pragma once
// gmsh keeps global state: one session per meshing or reading call, always
// finalized, so that a failure in one run never leaks a model into the next.
#include <gmsh.h>

namespace fc::feprep {

class GmshSession {
 public:
  explicit GmshSession(bool quiet) {
    gmsh::initialize(0, nullptr, false);
    gmsh::option::setNumber("General.Terminal", quiet ? 0 : 1);
    gmsh::option::setNumber("General.Verbosity", quiet ? 0 : 2);
  }
  ~GmshSession() { gmsh::finalize(); }
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;
};

}  // namespace fc::feprep
