// fe-prep-mpi and the tests: the file functions linked in.
#include "fe-prep/io/file_io.h"

namespace fc::feprep {

const FileIO& fileIO() { return linkedFileIO(); }

void requireFileIO() {}

void loadFileIOForWrite() {}

}  // namespace fc::feprep
