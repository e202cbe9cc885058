// Replays every fuzz target's seed corpus and regression inputs (tests/fuzz/corpus/TARGET,
// tests/fuzz/regressions/TARGET) in the ordinary suite, so the inputs that once crashed aesim,
// and the audit's reproducers, stay fixed in every build, the sanitizer build included: each must
// give a result or an InputError (the CLI tests in hostile_input_test check the refusals' words).
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <ostream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "fuzz/fuzz_targets.hpp"

namespace aesim {
namespace fuzz {
// CTest lists a case by its parameter's printout: the target's name, not its bytes.
void PrintTo(const Target& t, std::ostream* os) { *os << t.name; }
}  // namespace fuzz
namespace {
namespace fs = std::filesystem;

std::vector<std::string> files_in(const fs::path& dir) {
  std::vector<std::string> out;
  if (!fs::is_directory(dir)) return out;
  for (const auto& e : fs::directory_iterator(dir)) {
    if (e.is_regular_file()) out.push_back(e.path().string());
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

class FuzzReplay : public ::testing::TestWithParam<fuzz::Target> {};

TEST_P(FuzzReplay, EveryCorpusAndRegressionInputIsAResultOrAnInputError) {
  const fs::path root = fs::path(AESIM_SOURCE_DIR) / "tests" / "fuzz";
  const std::vector<std::string> corpus = files_in(root / "corpus" / GetParam().name);
  const std::vector<std::string> regressions = files_in(root / "regressions" / GetParam().name);
  EXPECT_FALSE(corpus.empty()) << "no seed corpus for " << GetParam().name;
  for (const std::vector<std::string>* set : {&corpus, &regressions}) {
    for (const std::string& path : *set) {
      SCOPED_TRACE(path);
      const std::string data = slurp(path);
      EXPECT_EQ(GetParam().run(reinterpret_cast<const std::uint8_t*>(data.data()), data.size()), 0);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Targets, FuzzReplay, ::testing::ValuesIn(fuzz::kTargets),
                         [](const ::testing::TestParamInfo<fuzz::Target>& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace aesim
