#pragma once
// The benchmarks' rigid chain (bench_mbs ChainRightHandSide, bench_integrators
// table C): n rods (0.1 m, 0.1 kg) on revolute joints about y, laid out along
// +x from the ground's origin, gravity along -z; `simulation` is the scene's
// simulation block, e.g. "{t_end: 1}".
#include <string>

namespace fc::mbs::bench {

inline std::string rodChainScene(int n, const std::string& simulation) {
  std::string y = "bodies:\n  - {name: ground, rigid: {mass: 1, inertia: [[1,0,0],[0,1,0],[0,0,1]]}, fixed: true}\n";
  std::string j = "joints:\n";
  for (int k = 0; k < n; ++k) {
    y += "  - {name: L" + std::to_string(k) + ", rod: {length: 0.1, diameter: 0.01, mass: 0.1}, position: [" +
         std::to_string(0.05 + 0.1 * k) + ", 0, 0]}\n";
    const std::string prev = k ? "L" + std::to_string(k - 1) : "ground";
    const std::string at = k ? "[0.05, 0, 0]" : "[0, 0, 0]";
    j += "  - {name: J" + std::to_string(k) + ", type: revolute, bodies: [" + prev + ", L" + std::to_string(k) +
         "], points: [" + at + ", [-0.05, 0, 0]], axes: [[0, 1, 0], [0, 1, 0]]}\n";
  }
  return y + j + "forces:\n  - {type: gravity, g: [0, 0, -9.81]}\nsimulation: " + simulation + "\n";
}

}  // namespace fc::mbs::bench
