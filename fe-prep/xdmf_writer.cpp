// XDMF for a flexible body file (see xdmf_writer.h). Every field is a plain
// HDF dataset of the body file: the per-mode translations and rotations are the
// (n_nodes, 3) virtual views /view/mode_NN[_rotation] of /modes/shapes that
// writeFlexBody adds (common/flexbody.h), so nothing is stored twice and no
// XDMF hyperslab is needed. ParaView 5.11's legacy "XDMF Reader" read the
// former hyperslab items; its Xdmf3 readers skipped every one of them
// ("Skipping unrecognized array type"), which plain datasets avoid.
#include "fe-prep/xdmf_writer.h"

#include <cstdio>
#include <sstream>
#include <vector>

#include "common/files.h"
#include "common/flexbody.h"

namespace fc::feprep {

namespace {

std::string baseName(const std::string& path) {
  const auto slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

// XML attribute text: the file name is the only free text we emit.
std::string xmlEscape(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

void hdfItem(std::ostringstream& x, const std::string& dims, const char* number_type, int precision,
             const std::string& h5, const std::string& dataset, const std::string& indent) {
  x << indent << "<DataItem Dimensions=\"" << dims << "\" NumberType=\"" << number_type << "\" Precision=\""
    << precision << "\" Format=\"HDF\">" << h5 << ":" << dataset << "</DataItem>\n";
}

// A node-centred field read from dataset `dataset` of the body file, (n, components).
void nodeAttribute(std::ostringstream& x, const std::string& name, const char* type, long n, int components,
                   const std::string& h5, const std::string& dataset) {
  x << "      <Attribute Name=\"" << name << "\" AttributeType=\"" << type << "\" Center=\"Node\">\n";
  hdfItem(x, std::to_string(n) + (components > 1 ? " " + std::to_string(components) : ""), "Float", 8, h5, dataset,
          "        ");
  x << "      </Attribute>\n";
}

}  // namespace

std::string xdmfPathFor(const std::string& h5_path) {
  const auto slash = h5_path.find_last_of('/');
  const auto dot = h5_path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return h5_path + ".xdmf";
  return h5_path.substr(0, dot) + ".xdmf";
}

std::string modeFieldName(int mode_index, double frequency_hz) {
  // Four significant digits, never an exponent (a field name is read, not parsed).
  char freq[64];
  if (frequency_hz >= 1000.0)
    std::snprintf(freq, sizeof freq, "%.0f", frequency_hz);
  else
    std::snprintf(freq, sizeof freq, "%.4g", frequency_hz);
  if (std::string(freq).find('e') != std::string::npos) std::snprintf(freq, sizeof freq, "%.6f", frequency_hz);
  char name[96];
  std::snprintf(name, sizeof name, "mode_%02d_%sHz", mode_index + 1, freq);
  return name;
}

std::string bodyXdmf(const std::string& h5_path, const FlexBody& body) {
  const std::string h5 = xmlEscape(baseName(h5_path));
  const long n = body.nodeCount();
  const int nm = body.modeCount();
  std::ostringstream x;
  x << "<?xml version=\"1.0\" ?>\n"
    << "<!-- Written by fe-prep beside " << h5 << ": open this file in ParaView with any of its XDMF readers. "
    << "Mode fields are per unit modal coordinate (kg^-1/2). -->\n"
    << "<Xdmf Version=\"2.0\">\n  <Domain>\n";
  // One grid per element kind the body has (shell triangles, beam lines).
  struct Kind {
    const char* dataset;
    const char* topology;
    int per_cell;
  };
  std::vector<std::pair<Kind, long>> grids;
  for (const Kind k : {Kind{"triangles", "Triangle", 3}, Kind{"beams", "Polyline", 2}}) {
    auto it = body.elements.find(k.dataset);
    if (it != body.elements.end() && it->second.rows() > 0) grids.emplace_back(k, it->second.rows());
  }
  if (grids.empty()) grids.emplace_back(Kind{nullptr, "Polyvertex", 1}, n);  // nodes only
  const bool collection = grids.size() > 1;
  if (collection) x << "  <Grid Name=\"" << xmlEscape(body.name) << "\" GridType=\"Collection\" CollectionType=\"Spatial\">\n";
  for (const auto& [kind, cells] : grids) {
    const std::string grid_name = collection ? std::string(kind.dataset) : body.name;
    x << "    <Grid Name=\"" << xmlEscape(grid_name) << "\" GridType=\"Uniform\">\n";
    if (kind.dataset) {
      x << "      <Topology TopologyType=\"" << kind.topology << "\" NumberOfElements=\"" << cells << "\""
        << (kind.per_cell == 2 ? " NodesPerElement=\"2\"" : "") << ">\n";
      hdfItem(x, std::to_string(cells) + " " + std::to_string(kind.per_cell), "Int", 8, h5,
              std::string("/mesh/") + kind.dataset, "        ");
      x << "      </Topology>\n";
    } else {
      x << "      <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"" << n << "\" NodesPerElement=\"1\"/>\n";
    }
    x << "      <Geometry GeometryType=\"XYZ\">\n";
    hdfItem(x, std::to_string(n) + " 3", "Float", 8, h5, "/mesh/nodes", "        ");
    x << "      </Geometry>\n";
    // Lumped nodal mass (column 0 of /mass/nodal): shows where the mass sits.
    nodeAttribute(x, "nodal_mass", "Scalar", n, 1, h5, "/view/nodal_mass");
    for (int j = 0; j < nm; ++j) {
      const std::string name = modeFieldName(j, body.frequencies_hz(j));
      const std::string view = "/view/" + modeViewName(j);
      nodeAttribute(x, name, "Vector", n, 3, h5, view);
      nodeAttribute(x, name + "_rotation", "Vector", n, 3, h5, view + "_rotation");
    }
    x << "    </Grid>\n";
  }
  if (collection) x << "  </Grid>\n";
  x << "  </Domain>\n</Xdmf>\n";
  return x.str();
}

}  // namespace fc::feprep
