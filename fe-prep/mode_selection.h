#pragma once
// Which solved eigenpairs a reduction keeps: the same rule for both linear
// algebra backends (fe-prep/modal_solver.cpp on SLEPc, fe-prep/la/serial/
// arpack_modes.cpp on ARPACK), on the pairs' eigenvalues and rigid shares only.
#include <cstddef>
#include <optional>
#include <vector>

namespace fc::feprep {

struct SolvedPair {
  double lambda = 0.0;       // omega^2
  double rigid_share = 0.0;  // b^T G^-1 b of the M-normalised vector (modal_solver.h)
};

struct ModeSelection {
  std::vector<std::size_t> kept;     // indices of the kept elastic pairs, ascending lambda
  std::vector<std::size_t> removed;  // indices of the rigid ones, ascending lambda
};

// The r_solved pairs with the largest rigid share are the rigid ones; the
// others are elastic, kept in ascending order: all those up to lambda_max
// when it is > 0, else the lowest `wanted`. Empty when lambda_max asks for
// more than was solved (every elastic pair below it and the solve not
// `exhausted`): the caller solves for more.
std::optional<ModeSelection> selectModes(const std::vector<SolvedPair>& pairs, long r_solved, double lambda_max,
                                         bool exhausted, long wanted);

}  // namespace fc::feprep
