#pragma once
#include <cstddef>
#include <utility>
#include <vector>

namespace aesim {

// The Pareto front of points scored on two objectives, both lower-is-better (negate one that is
// higher-is-better): the indices of the points that no other point matches in both and beats in
// one, in input order. A point with a NaN score is never on the front and dominates none.
std::vector<std::size_t> pareto_front(const std::vector<std::pair<double, double>>& scores);

}  // namespace aesim
