// Compiled against one layer's target with a header of the layer above it (AESIM_PROBE_HEADER):
// the build must fail to find the header (tests/CMakeLists.txt, layering.*).
#include AESIM_PROBE_HEADER
