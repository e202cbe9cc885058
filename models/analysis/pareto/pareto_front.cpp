#include "aesim/pareto/pareto_front.hpp"

#include <algorithm>
#include <cmath>

namespace aesim {

std::vector<std::size_t> pareto_front(const std::vector<std::pair<double, double>>& scores) {
  std::vector<std::size_t> front;
  for (std::size_t i = 0; i < scores.size(); ++i) {
    const double a = scores[i].first, b = scores[i].second;
    if (std::isnan(a) || std::isnan(b)) continue;
    const bool dominated = std::any_of(scores.begin(), scores.end(), [&](const std::pair<double, double>& o) {
      return o.first <= a && o.second <= b && (o.first < a || o.second < b);
    });
    if (!dominated) front.push_back(i);
  }
  return front;
}

}  // namespace aesim
