#pragma once
// gmsh input files are programs: a .geo script can run shell commands (System,
// SystemCall), end the calling process with status 0 (Exit, Abort), read or write
// arbitrary files (Include, Merge, Save, Print, Printf > file) or sleep. flexcomp
// reads geometry only, so before gmsh opens a file:
//   - only .geo (a script) and .msh (data) files are accepted;
//   - a .geo file is scanned (comments and strings skipped) and any of those
//     commands is an InputError naming the file, line and column.
// gmsh has no option that disables these commands, hence the scan.
#include <string>
#include <vector>

namespace fc {

void checkGmshInput(const std::string& path);

// An ASCII .msh file (MSH 2.2 or 4.x) read before gmsh sees it: a section
// without its end, a count that does not match the lines that follow, a node
// or element number given twice, an element naming a node that does not
// exist, a non-finite coordinate are InputErrors at their line. gmsh 4.8
// reads past such files: an element line given twice made it drop the last
// element without a word (its count was reached), a missing $Nodes header
// line crashed it ("double free or corruption"). Binary files are left to gmsh.
void checkMshStructure(const std::string& path);
// The refused .geo commands (for documentation and tests).
const std::vector<std::string>& refusedGeoCommands();


}  // namespace fc
