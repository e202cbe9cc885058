#pragma once
#include <optional>
#include <string>
#include <vector>

namespace aesim {

// The name among `names` a mistyped `given` most likely meant, for "did you mean" hints: the
// closest by edit distance (insertions, deletions, substitutions, and a swap of neighbours), case
// ignored, when at most a third of the longer name differs (at least one edit allowed); or the one
// whose part after the last '.' is `given` ("c_int" for "pixel.c_int"). Nothing when none is close.
std::optional<std::string> nearest_name(const std::string& given, const std::vector<std::string>& names);

// ", did you mean 'NAME'?" for an error message, or "" when no name is close.
std::string did_you_mean(const std::string& given, const std::vector<std::string>& names);

}  // namespace aesim
