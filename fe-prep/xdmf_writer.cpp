// XDMF for a flexible body file (see xdmf_writer.h). The mode shapes are
// stored as one (n_modes, n_nodes, 6) array; each mode's translations and
// rotations are (1, n_nodes, 3) hyperslabs of it, so nothing is duplicated.
// Written in XDMF 2 syntax: ParaView 5.11's "XDMF Reader" reads attribute
// hyperslabs, its Xdmf3 readers do not (measured: arrays skipped or a crash),
// and per-mode copies of the shapes would double the body file.
#include "fe-prep/xdmf_writer.h"

#include <cstdio>
#include <sstream>
#include <vector>

#include "common/files.h"

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

// A (1, n, 3) hyperslab of /modes/shapes starting at column `first` (0: u, 3: theta).
void modeAttribute(std::ostringstream& x, const std::string& name, int mode, int first, long n, int nm,
                   const std::string& h5) {
  x << "      <Attribute Name=\"" << name << "\" AttributeType=\"Vector\" Center=\"Node\">\n"
    << "        <DataItem ItemType=\"HyperSlab\" Dimensions=\"" << n << " 3\" Type=\"HyperSlab\" NumberType=\"Float\" Precision=\"8\">\n"
    << "          <DataItem Dimensions=\"3 3\" NumberType=\"Int\" Format=\"XML\">" << mode << " 0 " << first
    << " 1 1 1 1 " << n << " 3</DataItem>\n";
  hdfItem(x, std::to_string(nm) + " " + std::to_string(n) + " 6", "Float", 8, h5, "/modes/shapes", "          ");
  x << "        </DataItem>\n      </Attribute>\n";
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
    << "<!-- Written by fe-prep beside " << h5 << ": open this file in ParaView with the \"XDMF Reader\". "
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
    x << "      <Attribute Name=\"nodal_mass\" AttributeType=\"Scalar\" Center=\"Node\">\n"
      << "        <DataItem ItemType=\"HyperSlab\" Dimensions=\"" << n << " 1\" Type=\"HyperSlab\" NumberType=\"Float\" Precision=\"8\">\n"
      << "          <DataItem Dimensions=\"3 2\" NumberType=\"Int\" Format=\"XML\">0 0 1 1 " << n << " 1</DataItem>\n";
    hdfItem(x, std::to_string(n) + " 4", "Float", 8, h5, "/mass/nodal", "          ");
    x << "        </DataItem>\n      </Attribute>\n";
    for (int j = 0; j < nm; ++j) {
      const std::string name = modeFieldName(j, body.frequencies_hz(j));
      modeAttribute(x, name, j, 0, n, nm, h5);
      modeAttribute(x, name + "_rotation", j, 3, n, nm, h5);
    }
    x << "    </Grid>\n";
  }
  if (collection) x << "  </Grid>\n";
  x << "  </Domain>\n</Xdmf>\n";
  return x.str();
}

}  // namespace fc::feprep
