#include "aesim/text/nearest_name.hpp"

#include <algorithm>
#include <cstddef>

#include "aesim/text/ascii_case.hpp"

namespace aesim {
namespace {

// Optimal string alignment distance: a transposed pair ("c_itn") counts as one typing slip.
std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::vector<std::size_t>> d(a.size() + 1, std::vector<std::size_t>(b.size() + 1));
  for (std::size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
  for (std::size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  }
  return d[a.size()][b.size()];
}

}  // namespace

std::optional<std::string> nearest_name(const std::string& given, const std::vector<std::string>& names) {
  const std::string g = ascii_lower(given);
  // Bounded first: a name far longer than any key is no typing slip, and its table would be large.
  if (g.empty() || g.size() > 256) return std::nullopt;
  for (const std::string& n : names) {
    const auto dot = n.rfind('.');
    if (dot != std::string::npos && ascii_lower(n.substr(dot + 1)) == g) return n;
  }
  std::optional<std::string> best;
  std::size_t best_distance = 0;
  for (const std::string& n : names) {
    const std::string l = ascii_lower(n);
    const std::size_t allowed = std::max<std::size_t>(1, std::max(l.size(), g.size()) / 3);
    const std::size_t d = edit_distance(g, l);
    if (d <= allowed && (!best || d < best_distance)) {
      best = n;
      best_distance = d;
    }
  }
  return best;
}

std::string did_you_mean(const std::string& given, const std::vector<std::string>& names) {
  const std::optional<std::string> n = nearest_name(given, names);
  return n ? ", did you mean '" + *n + "'?" : std::string();
}

}  // namespace aesim
