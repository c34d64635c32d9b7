// The module the serial program loads (libflexcomp_feprep_h5.so): its one
// entry point hands out the file table. The module carries its own copy of
// flexcomp_base, but the program exports its fc:: symbols (exports.list), so
// the module's calls into them (the temporaries a signal removes, the input
// files an output must not overwrite, the stage an out-of-memory message names)
// reach the program's one copy.
#include "fe-prep/io/file_io.h"

extern "C" __attribute__((visibility("default"))) const fc::feprep::FileIO* flexcomp_feprep_file_io() {
  return &fc::feprep::linkedFileIO();
}
