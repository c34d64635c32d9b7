#pragma once
// A Nastran bulk-data deck as the mesh and properties of a body (contracts.md,
// "General bodies"; the subset and where it differs from Nastran: docs/nastran.md).
//
// Two layers: readNastranCards turns the text (free, small and large field,
// continuations, INCLUDE, BEGIN BULK / ENDDATA, $ comments) into cards whose
// every field remembers its file and line; nastranMesh turns the cards into the
// body's Mesh with each element's property and material frame, the node sets
// (SPC1 sets as SPC<id>, RBE2/RBE3 patches as RBE<eid>), the concentrated
// masses (CONM2) and the deck's own interfaces (GRID and RBE ids).
// applyNastranDeck does both for a body YAML and resolves `{grid: ID}` and
// `{rbe: EID}` interfaces, `regions: {PID<n>: ...}` overrides and SPC sets.
#include <Eigen/Dense>
#include <map>
#include <string>
#include <vector>

#include "common/units.h"
#include "fe-prep/body_spec.h"
#include "fe-prep/mesh.h"

namespace fc::feprep {

// One field of a card: its text (trimmed, upper case) and its line (in the
// card's file: NastranCard::fileOf). 40 bytes: a 1e6-element deck holds ~1.6e7.
struct NastranField {
  std::string text;
  int line = 0;
};

// A card: its name (GRID, CQUAD4...) and data fields in Nastran's numbering:
// fields[0] is field 2 of the first line, continuation rows follow with 8 data
// fields each (fields 10 and 1 of a continuation, the markers, are dropped).
struct NastranCard {
  std::string name;
  std::string file;
  int line = 0;
  std::vector<NastranField> fields;
  // Continuation rows read from another file than the card's (an INCLUDE
  // between a card and its continuation): (first field index, file).
  std::vector<std::pair<std::size_t, std::string>> other_files;
  const std::string& fileOf(std::size_t field) const;
};

// Reads a deck (following INCLUDE relative to the including file). Refused with
// an InputError naming file and line: unreadable files, a continuation with no
// card before it, a free-field line of more than 10 fields, a large-field card
// whose continuation is missing. Lines before BEGIN BULK (when present) and
// after ENDDATA are skipped.
std::vector<NastranCard> readNastranCards(const std::string& path);

// Is this file a Nastran deck by its extension (.bdf, .dat, .nas, .bulk)?
bool isNastranFile(const std::string& path);

struct NastranRbe {
  long eid = 0;
  bool rigid = true;                  // RBE2; else RBE3
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  // GN (RBE2) or REFGRID (RBE3), SI
  long grid = 0;                      // its GRID id
  std::vector<long> nodes;            // the patch (mesh nodes)
  Eigen::VectorXd weights;            // RBE3: the deck's weights per patch node
  std::string where;                  // file:line of the card
};

struct NastranModel {
  Mesh mesh;                           // with properties, sets and point masses assigned
  std::map<long, long> node_of_grid;   // GRID id -> mesh node (grids used by elements)
  std::map<long, Eigen::Vector3d> grid_point;  // every GRID, basic system, SI
  std::map<long, NastranRbe> rbes;     // by element id
  std::map<long, std::string> spc_components;  // SPC1 set id -> components (123456 or 123)
  std::map<std::string, int> element_counts;   // CQUAD4, CTRIA3, CBAR... as read
};

// Converts the cards; units gives the deck's units (converted to SI), ignore the
// card names (and PID<n> properties) left out. Unsupported cards not ignored are
// one InputError listing each with its count and first line; a bad field names
// file, line, card, field number and what was expected.
NastranModel nastranModel(const std::vector<NastranCard>& cards, const UnitSystem& units,
                          const std::vector<std::string>& ignore);

// For a body whose mesh file is a Nastran deck: reads it, applies regions:
// overrides (PID<n> entries replace the deck's property and give a shell its
// fibre axis, a beam its orientation), adds masses:, resolves {grid:}/{rbe:}
// interfaces (point, coupling, patch, RBE3 weights) and checks that reference
// sets SPC<id> are clamped (123456) or pinned (123) as the deck's SPC1 says.
// Leaves the finished mesh in spec.general->deck_mesh.
void applyNastranDeck(BodySpec& spec);

// PBARL BOX (Nastran's DIM1 = W along y, DIM2 = H along z, DIM3 = t1 of the top and
// bottom walls, DIM4 = t2 of the side walls), VABS order about the centroid.
SectionMatrices boxSection(double W, double H, double t1, double t2, double E, double nu, double rho);

}  // namespace fc::feprep
