#pragma once
// Builds parametric sections in code (no YAML) for the closed-form tests.
#include "common/materials.h"
#include "section-prep/cross_section.h"
#include "section-prep/section_mesher.h"
#include "section-prep/section_spec.h"

namespace fc::section::testing {

inline SectionMaterial isotropic(double E, double nu, double rho = 1000.0) {
  const Material m = makeIsotropic("iso", E, nu, rho);
  return {m.name, m.C, m.rho, std::nullopt};
}

inline SectionSpec solidCircle(double diameter, const SectionMaterial& m, double h) {
  SectionSpec s;
  s.shape = SectionSpec::Shape::SolidCircle;
  s.diameter = diameter;
  s.material = 0;
  s.materials = {m};
  s.mesh_size = h;
  return s;
}

inline SectionSpec tube(double outer_diameter, double t, const SectionMaterial& m, double h) {
  SectionSpec s;
  s.shape = SectionSpec::Shape::Tube;
  s.outer_diameter = outer_diameter;
  s.plies = {{0, t, 0.0}};
  s.materials = {m};
  s.mesh_size = h;
  return s;
}

inline SectionSpec rectangle(double width, double height, const SectionMaterial& m, double h) {
  SectionSpec s;
  s.shape = SectionSpec::Shape::Rectangle;
  s.width = width;
  s.height = height;
  s.material = 0;
  s.materials = {m};
  s.mesh_size = h;
  return s;
}

inline SectionProperties analyze(const SectionSpec& s) { return analyzeSection(meshSection(s)); }

}  // namespace fc::section::testing
