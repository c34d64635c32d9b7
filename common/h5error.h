#pragma once
// The error of a flexcomp HDF5 file (cannot open, wrong format, mis-shaped or
// non-finite dataset): its message names the file. Apart from h5io.h so that code
// that only catches it (fc::guardedMain) does not include HDF5.
#include <stdexcept>

namespace fc {

class H5Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace fc
