// jemalloc's settings for the executables that link it (the aesim program and the benchmarks),
// read by jemalloc from this symbol when the process starts.
//
// thp:always puts the heap on 2 MiB transparent huge pages (madvise, so it holds on a system whose
// THP mode is "madvise", Debian's default). A large array's run touches hundreds of MiB once, a
// window's buffers of thousands of tiles and their pixels' schedules: on 4 KiB pages every page is
// a fault (about 146 k for a 2048x2048 AEDAT run, a second of system time on a virtual machine
// whose faults trap to the hypervisor; 6 k on 2 MiB pages), and the merge, reading a slice of each
// of 4,096 tiles in turn, misses the TLB on each. docs/performance.md has the figures.
extern "C" {
extern const char* malloc_conf;
const char* malloc_conf = "thp:always";
}
