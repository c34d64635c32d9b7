#include "fe-prep/mode_selection.h"

#include <algorithm>
#include <numeric>

namespace fc::feprep {

std::optional<ModeSelection> selectModes(const std::vector<SolvedPair>& pairs, long r_solved, double lambda_max,
                                         bool exhausted, long wanted) {
  std::vector<std::size_t> order(pairs.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return pairs[a].rigid_share > pairs[b].rigid_share; });
  ModeSelection s;
  for (std::size_t k = 0; k < order.size(); ++k) (static_cast<long>(k) < r_solved ? s.removed : s.kept).push_back(order[k]);
  auto by_lambda = [&](std::size_t a, std::size_t b) { return pairs[a].lambda < pairs[b].lambda; };
  std::sort(s.kept.begin(), s.kept.end(), by_lambda);
  std::sort(s.removed.begin(), s.removed.end(), by_lambda);
  if (lambda_max > 0 && !exhausted && (s.kept.empty() || pairs[s.kept.back()].lambda <= lambda_max)) return std::nullopt;
  std::size_t keep = s.kept.size();
  if (lambda_max > 0) {
    keep = 0;
    while (keep < s.kept.size() && pairs[s.kept[keep]].lambda <= lambda_max) ++keep;
  } else {
    keep = std::min<std::size_t>(keep, static_cast<std::size_t>(std::max<long>(wanted, 0)));
  }
  s.kept.resize(keep);
  return s;
}

}  // namespace fc::feprep
