#pragma once
// Reading a scene file (contracts.md, "mbs-run", plus the extensions in
// docs/mbs-run.md) into a Model. Every error is an fc::InputError naming the
// file, line, key, what is wrong and what is expected.
#include <string>

#include "common/input.h"
#include "mbs-run/model/model.h"

namespace fc::mbs {

Model loadScene(const std::string& path);
Model parseScene(const fc::InputNode& root);

}  // namespace fc::mbs
