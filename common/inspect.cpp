#include "common/inspect.h"

#include <iomanip>
#include <sstream>

#include "common/h5io.h"

namespace fc {

namespace {

void listDataset(const H5File& f, const std::string& path, std::ostringstream& os) {
  try {
    const auto dims = f.shape(path);
    os << "  (";
    for (std::size_t i = 0; i < dims.size(); ++i) os << (i ? ", " : "") << dims[i];
    os << ")";
    if (dims.empty() || (dims.size() == 1 && dims[0] == 1)) {
      try {
        const double v = f.readScalar(path);
        os << " = " << v;
      } catch (const H5Error&) {
        try {
          const std::string v = f.readString(path);
          os << " = \"" << v << "\"";
        } catch (const H5Error&) {
        }
      }
    }
  } catch (const H5Error&) {
    os << "  (unreadable)";
  }
  os << "\n";
}

// A damaged or hostile file can link a group into itself or an ancestor: walkTree
// enters each group once; the depth limit keeps a legitimately deep file readable.
void listDatasets(const H5File& f, std::ostringstream& os) {
  using Kind = H5TreeEntry::Kind;
  walkTree(f, "/", [&](const H5TreeEntry& e) {
    const std::string indent(static_cast<std::size_t>(2 * e.depth + 2), ' ');
    os << indent << e.name;
    if (e.kind == Kind::Group) os << "/";
    if (!e.target.empty()) os << " -> " << e.target;
    switch (e.kind) {
      case Kind::Dataset:
        listDataset(f, e.path, os);
        return false;
      case Kind::External:
        os << "  (external link: not followed)\n";
        return false;
      case Kind::Dangling:
        os << "  (link to nothing)\n";
        return false;
      case Kind::Other:
        os << "  (neither group nor dataset)\n";
        return false;
      case Kind::Group:
        break;
    }
    if (e.seen_before) {
      os << "  (a group met above, through another link: not entered again)\n";
      return false;
    }
    os << "\n";
    if (e.depth >= 16) {
      os << indent << "  (nested deeper than 16 groups: not listed)\n";
      return false;
    }
    // Interfaces and bodies can be many: list their names only past a few.
    const auto kids = f.children(e.path);
    if (e.depth >= 1 && kids.size() > 12) {
      os << indent << "  (" << kids.size() << " entries)\n";
      return false;
    }
    return true;
  });
}

void summarise(const H5File& f, const std::string& kind, std::ostringstream& os) {
  os << std::setprecision(6);
  if (kind == "section" && f.exists("/stiffness/timoshenko")) {
    const Eigen::MatrixXd K = f.readMatrix("/stiffness/timoshenko", 6, 6);
    os << "summary: EA = " << K(0, 0) << " N, GA2 = " << K(1, 1) << " N, GA3 = " << K(2, 2)
       << " N, GJ = " << K(3, 3) << " N m^2, EI2 = " << K(4, 4) << " N m^2, EI3 = " << K(5, 5)
       << " N m^2";
    if (f.exists("/mass/per_length")) os << ", mass " << f.readScalar("/mass/per_length") << " kg/m";
    os << "\n";
  } else if (kind == "flexbody") {
    if (f.exists("/inertia/mass")) os << "summary: mass " << f.readScalar("/inertia/mass") << " kg";
    if (f.exists("/mesh/nodes")) {
      const auto dims = f.shape("/mesh/nodes");
      if (!dims.empty()) os << ", " << dims[0] << " nodes";
    }
    if (f.exists("/modes/frequencies_hz")) {
      const Eigen::VectorXd fr = f.readVector("/modes/frequencies_hz");
      os << ", " << fr.size() << " modes\n  frequencies [Hz]:";
      for (Eigen::Index i = 0; i < fr.size(); ++i) os << " " << fr(i);
    }
    os << "\n";
    if (f.exists("/interfaces")) {
      os << "  interfaces:";
      for (const auto& n : f.children("/interfaces")) os << " " << n;
      os << "\n";
    }
    // A general body's regions (/regions/NAME): kind, element counts, mass, material axes.
    if (f.exists("/regions")) {
      os << "  regions:\n";
      for (const auto& n : f.children("/regions")) {
        const std::string g = "/regions/" + n;
        auto attr = [&](const char* a) { return f.hasAttribute(g, a) ? f.stringAttribute(g, a) : std::string(); };
        const std::string kind_r = attr("kind"), of = attr("members_of"), element = attr("element");
        const long count = f.exists(g + "/members") ? static_cast<long>(f.readIntVector(g + "/members").size()) : 0;
        os << "    " << (attr("name").empty() ? n : attr("name")) << ": " << kind_r << ", " << count << " "
           << (of == "triangles" ? "triangles" : of == "beams" ? "beam elements" : count == 1 ? "node" : "nodes");
        if (!element.empty()) os << " (" << element << ")";
        if (f.exists(g + "/mass")) os << ", " << f.readScalar(g + "/mass") << " kg";
        if (!attr("property").empty()) os << (kind_r == "shell" ? ", laminate " : ", section ") << attr("property");
        if (!attr("axis").empty()) os << ", " << attr("axis");
        os << "\n";
      }
    }
  } else if (kind == "results" && f.exists("/time")) {
    const Eigen::VectorXd t = f.readVector("/time");
    os << "summary: " << t.size() << " outputs";
    if (t.size() > 0) os << ", t = " << t(0) << " .. " << t(t.size() - 1) << " s";
    if (f.hasAttribute("/", "status")) os << ", status: " << f.stringAttribute("/", "status");
    if (f.hasAttribute("/", "cpu_seconds"))
      os << ", cpu " << f.doubleAttribute("/", "cpu_seconds") << " s";
    os << "\n";
    if (f.exists("/bodies")) {
      os << "  bodies:";
      for (const auto& n : f.children("/bodies")) os << " " << n;
      os << "\n";
    }
  }
}

}  // namespace

std::string inspectFile(const std::string& path) {
  H5File f(path, H5File::Mode::Read);
  std::ostringstream os;
  os << path << "\n";
  std::string kind;
  for (const char* attr : {"format", "units", "tool", "version", "created", "inputs_sha256",
                           "status"}) {
    if (!f.hasAttribute("/", attr)) continue;
    const std::string v = f.stringAttribute("/", attr);
    os << "  " << attr << ": " << v << "\n";
    if (std::string(attr) == "format") kind = v.substr(0, v.find('/'));
  }
  // A damaged file still gets its datasets listed: the summary is best effort.
  try {
    std::ostringstream summary;  // whole or not at all: no half line before the reason
    summary << std::setprecision(6);
    summarise(f, kind, summary);
    os << summary.str();
  } catch (const H5Error& e) {
    os << "summary: not available (" << e.what() << ")\n";
  }
  os << "datasets:\n";
  listDatasets(f, os);
  return os.str();
}

}  // namespace fc
