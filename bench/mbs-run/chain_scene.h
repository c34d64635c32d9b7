#pragma once
// The benchmarks' rigid chain (bench_mbs ChainRightHandSide, bench_integrators
// table C, bench_chains): n rods (0.1 m, 0.1 kg) on revolute joints about y,
// laid out along +x from the ground's origin, gravity along -z; `simulation`
// is the scene's simulation block, e.g. "{t_end: 1}". Shared with the tests
// (tests/mbs-run/chain_reference.h).
#include "../../tests/mbs-run/chain_reference.h"

namespace fc::mbs::bench {

using fc::mbs::test::rodChainScene;

}  // namespace fc::mbs::bench
