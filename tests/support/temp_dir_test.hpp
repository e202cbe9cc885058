#pragma once
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

namespace aesim::testing {

inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

struct Outcome {
  int status = -1;
  std::string out, err;
};

// A test with its own empty folder (removed afterwards), in which it can write inputs and run
// the aesim program as a user would.
class TempDirTest : public ::testing::Test {
 protected:
  void SetUp() override {
    // A parameterised test's names hold '/' (Receivers/MutantTest): one folder, not a parent
    // that removing the child would leave behind.
    std::string name = std::string(::testing::UnitTest::GetInstance()->current_test_info()->test_suite_name()) + "_" +
                       ::testing::UnitTest::GetInstance()->current_test_info()->name();
    for (char& c : name) {
      if (c == '/') c = '_';
    }
    dir_ = std::filesystem::temp_directory_path() / ("aesim_" + std::to_string(::getpid()) + "_" + name);
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  std::string write(const std::string& name, const std::string& bytes) {
    std::ofstream(dir_ / name, std::ios::binary) << bytes;
    return (dir_ / name).string();
  }

#ifdef AESIM_BINARY
  // Runs `aesim ARGS` in the folder and captures its exit status, stdout and stderr. `prefix`
  // goes before the program (e.g. "timeout 60 ").
  Outcome aesim(const std::string& args, const std::string& prefix = "") {
    const std::string cmd =
        "cd '" + dir_.string() + "' && " + prefix + "'" AESIM_BINARY "' " + args + " >stdout.txt 2>stderr.txt";
    Outcome o;
    const int raw = std::system(cmd.c_str());
    o.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    o.out = slurp(dir_ / "stdout.txt");
    o.err = slurp(dir_ / "stderr.txt");
    std::filesystem::remove(dir_ / "stdout.txt");
    std::filesystem::remove(dir_ / "stderr.txt");
    return o;
  }
  // `aesim run` on a scene it must refuse: exit status 2, one line of error holding `needle`, and
  // the output it was asked for not written.
  void expect_scene_refused(const std::string& scene, const std::string& needle) {
    const Outcome run = aesim("run --scene '" + scene + "' --duration 10ms --csv e.csv");
    EXPECT_EQ(run.status, 2) << needle;
    EXPECT_NE(run.err.find(needle), std::string::npos) << run.err;
    EXPECT_EQ(run.err.find('\n'), run.err.size() - 1) << run.err;
    EXPECT_FALSE(std::filesystem::exists(dir_ / "e.csv")) << needle;
  }
#endif

  std::filesystem::path dir_;
};

}  // namespace aesim::testing
