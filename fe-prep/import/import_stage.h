#pragma once
// The stages an imported body (body.matrices) adds to buildFlexBody: reading and
// checking the model, the report that compares it with its source (storage,
// mass, centre, inertia, first frequencies next to the source code's own), the
// nodal masses fitted to the imported M, and the checks of interfaces on solid
// nodes. Kept apart so that build_body.cpp only branches into them.
#include <string>

#include "fe-prep/body_inertia.h"
#include "fe-prep/body_spec.h"
#include "fe-prep/import/imported_body.h"
#include "fe-prep/interfaces.h"
#include "la_backend.h"

namespace fc::feprep {

// Reads the model on every rank (the same files, the same errors) and, on rank
// 0 unless quiet, prints the import report; warns (stderr, naming the quantity)
// where the imported matrices disagree with the source beyond 1e-6 relative.
ImportedModel importStage(Comm comm, const BodySpec& spec, bool quiet);

// The first `count` elastic eigenvalues [rad^2/s^2] of the free imported K, M
// (SLEPc, the same solver as the body's modes).
Eigen::VectorXd importedFreeEigenvalues(Comm comm, const ImportedModel& model, long count);

// /mass/nodal of an imported body (importedNodalMasses), with a warning when the
// fit could not be applied.
ImportedLumping importedLumping(Comm comm, const ImportedModel& model, bool quiet);

// The exact rigid-body properties: the projection of the imported M.
RigidProperties importedRigidProperties(const ImportedModel& model);

// A point interface on a solid node would carry no rotation (refused). A
// distributing patch of an imported body is weighed by the solid elements'
// faces that lie wholly in it (patchFaceWeights, solid_faces.h: each node's
// integral of its face shape functions, as CalculiX's *DISTRIBUTING); with no
// such face (6-DOF nodes, or a patch narrower than a face) its nodes weigh
// equally. W recomputed here; returns the line the import report prints.
std::string checkImportedInterface(const ImportedModel& model, MeshInterface& mi, const InterfaceSpec& spec);

}  // namespace fc::feprep
