// GTKWave's FST library (reader and writer), for builds whose Verilator writes FST with
// a writer of its own and ships no reader (5.04x: fstcpp). sim/sm_wave_names.hpp reads
// FST files with it. Compiled as C++ the way Verilator 5.006's verilated_fst_c.cpp
// compiles it; LZ4 comes from the system library (cmake/SmRtl.cmake).
#define HAVE_LIBPTHREAD
#define FST_CONFIG_INCLUDE "fst_config.h"
#include "gtkwave/fastlz.c"
#include "gtkwave/fstapi.c"
