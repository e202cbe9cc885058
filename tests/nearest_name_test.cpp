// The "did you mean" hints: hand-worked edit distances.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "aesim/text/nearest_name.hpp"

namespace aesim {
namespace {

const std::vector<std::string> kKeys = {"pixel.c_int", "pixel.dv_int", "pixel.i_dark", "bus.t_event", "sim.seed"};

TEST(NearestName, OneSlipFindsTheKey) {
  EXPECT_EQ(nearest_name("pixel.cint", kKeys), "pixel.c_int");      // a deletion
  EXPECT_EQ(nearest_name("pixel.c_itn", kKeys), "pixel.c_int");     // two neighbours swapped: one edit
  EXPECT_EQ(nearest_name("Pixel.C_Int", kKeys), "pixel.c_int");     // case is no slip
  EXPECT_EQ(nearest_name("bus.t_evnet", kKeys), "bus.t_event");
  EXPECT_EQ(nearest_name("sim.sead", kKeys), "sim.seed");
}

TEST(NearestName, TheKeyWithoutItsSectionFindsIt) { EXPECT_EQ(nearest_name("dv_int", kKeys), "pixel.dv_int"); }

TEST(NearestName, TheClosestWinsAndFarNamesGetNoHint) {
  // "pixel.i_dak" is one edit from i_dark and more from every other key.
  EXPECT_EQ(nearest_name("pixel.i_dak", kKeys), "pixel.i_dark");
  // "rnu" is two edits from "run" (a third of 3 characters rounds to 1 allowed, but the swap is one).
  EXPECT_EQ(nearest_name("rnu", {"run", "recon", "info"}), "run");
  EXPECT_EQ(nearest_name("xyz", {"run", "recon", "info"}), std::nullopt);
  EXPECT_EQ(nearest_name("array.rows", kKeys), std::nullopt);
  EXPECT_EQ(nearest_name("", kKeys), std::nullopt);
  EXPECT_EQ(nearest_name(std::string(10000, 'a'), kKeys), std::nullopt);
  EXPECT_EQ(did_you_mean("pixel.cint", kKeys), ", did you mean 'pixel.c_int'?");
  EXPECT_EQ(did_you_mean("array.rows", kKeys), "");
}

}  // namespace
}  // namespace aesim
