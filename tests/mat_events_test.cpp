// MATLAB files of events (.mat), written here by matio itself in the three versions MATLAB saves
// (4, 5 compressed, 7.3 on HDF5), laid out as the datasets that ship them do: ASL-DVS's vectors
// ts, x, y, pol of their own, and a TD struct as Garrick Orchard's Read_Ndataset makes it (x + 1,
// y + 1, p + 1: MATLAB's indices).
#include <matio.h>
#include <sys/resource.h>

#include <cstdint>
#include <fstream>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "aesim/errors/input_error.hpp"
#include "aesim/event_files/event_file.hpp"
#include "support/recorded_events.hpp"
#include "support/temp_dir_test.hpp"

namespace aesim {
namespace {

using testing::Cd;
using testing::expect_events;

// matio's class and storage type of a C++ number type.
template <typename T>
constexpr std::pair<matio_classes, matio_types> matio_type() {
  if constexpr (std::is_same_v<T, double>) return {MAT_C_DOUBLE, MAT_T_DOUBLE};
  if constexpr (std::is_same_v<T, std::uint8_t>) return {MAT_C_UINT8, MAT_T_UINT8};
  if constexpr (std::is_same_v<T, std::uint16_t>) return {MAT_C_UINT16, MAT_T_UINT16};
  if constexpr (std::is_same_v<T, std::uint32_t>) return {MAT_C_UINT32, MAT_T_UINT32};
  return {MAT_C_INT32, MAT_T_INT32};
}

// A column vector (N x 1, as MATLAB's and ASL-DVS's), its data left with the caller.
template <typename T>
matvar_t* column(const char* name, std::vector<T>& values) {
  std::size_t dims[2] = {values.size(), 1};
  constexpr auto type = matio_type<T>();
  return Mat_VarCreate(name, type.first, type.second, 2, dims, values.data(), MAT_F_DONT_COPY_DATA);
}

class MatFiles : public testing::TempDirTest {
 protected:
  // A file of `vars` (each freed here once written), in `version`.
  std::string write(const std::string& name, mat_ft version, const std::vector<matvar_t*>& vars) {
    const std::string path = (dir_ / name).string();
    mat_t* mat = Mat_CreateVer(path.c_str(), nullptr, version);
    EXPECT_NE(mat, nullptr);
    for (matvar_t* v : vars) {
      EXPECT_EQ(Mat_VarWrite(mat, v, version == MAT_FT_MAT5 ? MAT_COMPRESSION_ZLIB : MAT_COMPRESSION_NONE), 0);
      Mat_VarFree(v);
    }
    Mat_Close(mat);
    return path;
  }
};

void expect_refused(const std::string& path, const std::string& words) {
  testing::expect_refused_saying([&] { load_events(path); }, words);
}

// A 142-byte file the fuzzer made, whose header makes matio allocate and fill about 1 GB (1.09 GB
// resident and 1.8 s with the reader unbounded): refused with matio's own words, the
// reader (the forked copy, this test's only child) held to its budget of 256 MiB above what it
// was given. (Under AddressSanitizer the refused allocation ends the copy instead, which the
// error then says: the reader stopped before it finished.)
TEST(MatHostileFiles, AHeaderClaimingAGigabyteIsRefusedWithinTheReadersBudget) {
  const std::string path = std::string(AESIM_SOURCE_DIR) + "/tests/fuzz/regressions/mat/claims_a_gigabyte.mat";
  expect_refused(path, "event file '" + path + "': ");
  rusage children{};
  ASSERT_EQ(::getrusage(RUSAGE_CHILDREN, &children), 0);
  rusage self{};
  ASSERT_EQ(::getrusage(RUSAGE_SELF, &self), 0);
  EXPECT_LT(children.ru_maxrss, self.ru_maxrss + 300 * 1024) << "kB resident in the reader";
}

// ASL-DVS: double column vectors ts, x, y, pol (0 OFF, 1 ON), 0-based; the third event stamped
// before the second, read in time order and counted. The same in version 4 (no compression, no
// integers) and version 5 (zlib).
TEST_F(MatFiles, VectorsOfTheirOwnAreZeroBasedMicrosecondsInEveryVersion) {
  for (const mat_ft version : {MAT_FT_MAT4, MAT_FT_MAT5, MAT_FT_MAT73}) {
    SCOPED_TRACE(static_cast<int>(version));
    std::vector<double> ts = {100, 250, 200, 1000000}, x = {0, 239, 5, 7}, y = {0, 179, 6, 8}, pol = {1, 0, 1, 0};
    const std::string path = write("asl.mat", version, {column("ts", ts), column("x", x), column("y", y), column("pol", pol)});
    const EventRecording rec = load_events(path);
    expect_events(rec, {{100, 0, 0, true}, {200, 5, 6, true}, {250, 239, 179, false}, {1000000, 7, 8, false}});
    EXPECT_EQ(rec.reordered, 1u);
    EXPECT_FALSE(rec.size_recorded);
    EXPECT_TRUE(rec.read_as.empty());
  }
}

// Orchard's TD struct: integer fields x, y, p, ts counting from 1 (p 1 OFF, 2 ON), beside another
// variable; read one less, and said so.
TEST_F(MatFiles, AStructCountingFromOneAsMatlabDoesIsReadOneLess) {
  for (const mat_ft version : {MAT_FT_MAT5, MAT_FT_MAT73}) {
    SCOPED_TRACE(static_cast<int>(version));
    std::vector<std::uint16_t> x = {1, 34}, y = {1, 34};
    std::vector<std::uint8_t> p = {2, 1};
    std::vector<std::uint32_t> ts = {654, 311175};
    matvar_t* fields[5] = {column("x", x), column("y", y), column("p", p), column("ts", ts), nullptr};
    std::size_t one[2] = {1, 1};
    matvar_t* td = Mat_VarCreate("TD", MAT_C_STRUCT, MAT_T_STRUCT, 2, one, fields, 0);
    std::vector<double> label = {7};
    const std::string path = write("td.mat", version, {column("label", label), td});
    const EventRecording rec = load_events(path);
    expect_events(rec, {{654, 0, 0, true}, {311175, 33, 33, false}});
    ASSERT_EQ(rec.read_as.size(), 1u);
    EXPECT_EQ(rec.read_as[0], "TD counting from 1, as MATLAB does: x and y one less, polarity 2 ON and 1 OFF");
  }
}

// A stamp with a fraction is seconds (the vectors named t and p here, p -1 for OFF).
TEST_F(MatFiles, StampsWithFractionsAreSecondsRoundedToTheMicrosecond) {
  std::vector<double> t = {0.5, 1.0000014}, x = {3, 4}, y = {1, 2}, p = {-1, 1};
  const std::string path = write("sec.mat", MAT_FT_MAT5, {column("t", t), column("x", x), column("y", y), column("p", p)});
  const EventRecording rec = load_events(path);
  expect_events(rec, {{500000, 3, 1, false}, {1000001, 4, 2, true}});
  ASSERT_EQ(rec.read_as.size(), 1u);
  EXPECT_EQ(rec.read_as[0], "seconds: t has fractions");
}

TEST_F(MatFiles, FilesWithoutReadableEventsAreOneLineErrors) {
  std::vector<double> a = {1, 2, 3}, four = {0, 1, 2, 3};
  expect_refused(write("none.mat", MAT_FT_MAT5, {column("a", a), column("b", four)}),
                 "no vectors x, y, ts (or t) and pol (or p), as variables or the fields of a struct (it holds a (3x1), b (4x1))");
  std::vector<double> x = {1, 2, 3}, y = {1, 2, 3}, ts = {1, 2, 3}, p3 = {0, 1, 3};
  expect_refused(write("pol.mat", MAT_FT_MAT5, {column("x", x), column("y", y), column("ts", ts), column("pol", p3)}),
                 "event 2 has the polarity 3");
  std::vector<double> p = {0, 1, 1, 0};
  expect_refused(write("lengths.mat", MAT_FT_MAT5, {column("x", x), column("y", y), column("ts", ts), column("pol", p)}),
                 "pol holds 4 numbers where x holds 3");
  std::vector<double> zero = {0, 2, 3}, matlab = {1, 2, 2};
  expect_refused(write("index0.mat", MAT_FT_MAT5, {column("x", zero), column("y", y), column("ts", ts), column("p", matlab)}),
                 "event 0 at (0, 1) is not a pixel of a 4096x4096 array (MATLAB's indices, from 1)");
  std::vector<double> half = {1.5, 2, 3}, p01 = {0, 1, 1};
  expect_refused(write("half.mat", MAT_FT_MAT5, {column("x", half), column("y", y), column("ts", ts), column("p", p01)}),
                 "event 0 at (1.5, 1) is not a pixel");
  std::vector<double> back = {-5, 2, 3};
  expect_refused(write("negative.mat", MAT_FT_MAT5, {column("x", x), column("y", y), column("ts", back), column("p", p01)}),
                 "event 0 has the stamp -5");
  std::vector<double> re = {1, 2, 3}, im = {1, 0, 0};
  mat_complex_split_t split{re.data(), im.data()};
  std::size_t dims[2] = {3, 1};
  matvar_t* complex = Mat_VarCreate("x", MAT_C_DOUBLE, MAT_T_DOUBLE, 2, dims, &split, MAT_F_COMPLEX | MAT_F_DONT_COPY_DATA);
  expect_refused(write("complex.mat", MAT_FT_MAT5, {complex, column("y", y), column("ts", ts), column("p", p01)}), "x is complex");
  const std::string junk = (dir_ / "junk.mat").string();
  std::ofstream(junk) << "MATLAB 5.0 MAT-file, not really";
  expect_refused(junk, "event file '" + junk + "'");
  std::vector<double> big(4000, 1);
  const std::string good = write("cut.mat", MAT_FT_MAT5, {column("x", big), column("y", big), column("ts", big), column("p", big)});
  std::filesystem::resize_file(good, std::filesystem::file_size(good) / 2);
  expect_refused(good, "event file '" + good + "'");
}

}  // namespace
}  // namespace aesim
