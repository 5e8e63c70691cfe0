// The one Catch2 main of every unit test executable (tests/CMakeLists.txt): Catch2's
// implementation is compiled once instead of once per test.
#define CATCH_CONFIG_MAIN
#include <catch2/catch.hpp>
