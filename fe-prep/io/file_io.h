#pragma once
// fe-prep's HDF5 files behind one table of functions: the body file it writes,
// the section-prep files its beams read, `--inspect`.
//
// Why a table: the serial program (fe-prep) links no HDF5. HDF5 brings MPI,
// libcurl, gnutls and krb5 with it, 10 MB of resident memory before any work,
// which would sit under every factorisation of a small body. That program loads
// the table from a module (libflexcomp_feprep_h5.so, beside it in the build tree,
// in PREFIX/lib/flexcomp when installed) the first time it needs a file, after
// the factorisations are freed for the write. fe-prep-mpi and the tests link the
// same functions in (linkedFileIO). Both programs call fileIO().
#include <Eigen/Dense>
#include <string>

#include "common/flexbody.h"
#include "common/stress_data.h"

namespace fc::feprep {

// What a beam takes from a section-prep file (section/1).
struct SectionFile {
  Eigen::Matrix<double, 6, 6> stiffness;  // /stiffness/timoshenko
  Eigen::Matrix<double, 6, 6> mass;       // /mass/matrix
  SectionStressBasis stress_basis;        // /recovery/ (empty when not asked or absent)
};

struct FileIO {
  // fc::writeFlexBody: the body file, atomically.
  void (*write_body)(const std::string& path, const FlexBody& body, const InertiaInvariants& invariants,
                     const Provenance& provenance);
  // The section file's matrices (checked: format section/1, 6 x 6, finite) and,
  // when with_stress_basis, its stress recovery basis. Throws fc::H5Error naming
  // the file.
  SectionFile (*read_section)(const std::string& path, bool with_stress_basis);
  // fc::inspectFile.
  std::string (*inspect)(const std::string& path);
};

// The functions themselves (flexcomp_feprep_fileio): what fe-prep-mpi and the
// tests call, and what the module exports.
const FileIO& linkedFileIO();

// This program's table: linkedFileIO() where it is linked in, else the module's,
// loaded on the first call. Throws std::runtime_error naming the module and
// dlopen's reason when it cannot be loaded.
const FileIO& fileIO();

// Throws std::runtime_error, naming where it looked, when this program's table
// cannot be had (the serial program's module is missing): checked before the
// build, so that a broken installation costs no computing.
void requireFileIO();

// Frees what the heap holds unused (malloc_trim) and loads the table now: called
// before the write, once the factorisations are gone, so that the libraries
// land in memory the build gave back. A no-op where the table is linked in.
void loadFileIOForWrite();

}  // namespace fc::feprep
