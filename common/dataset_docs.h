#pragma once
// What every dataset of the three file formats means, and its units: one table
// that annotates the files (each dataset gets `units` and `description`
// attributes when it is written, so h5dump, h5py and ParaView users see them) and
// that docs/file-formats.md is checked against.
#include <string>
#include <vector>

#include "common/h5io.h"

namespace fc {

struct DatasetDoc {
  std::string format;   // "section", "flexbody", "results"
  std::string pattern;  // absolute path; '*' matches one path segment
  std::string units;
  std::string description;
};

const std::vector<DatasetDoc>& datasetDocs();

// The entry matching `path` in a file of kind `format`, or nullptr.
const DatasetDoc* findDatasetDoc(const std::string& format, const std::string& path);

// Sets `units` and `description` on every dataset of `f` that the table knows
// and that has no such attributes yet. The file's kind is read from its root
// `format` attribute; a file without one is left as it is.
void annotateDatasets(H5File& f);

}  // namespace fc
