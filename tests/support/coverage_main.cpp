// The coverage run: every directed test in one process; each bench writes its Verilator
// coverage counts to $AESIM_COVERAGE_DIR/coverage_N.dat while its model is alive.
#include <gtest/gtest.h>
#include <systemc>

int sc_main(int argc, char* argv[]) {
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
