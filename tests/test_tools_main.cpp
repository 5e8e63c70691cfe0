// Catch2 main shared by the tool tests (compiled once).
#define CATCH_CONFIG_MAIN
#include <catch2/catch.hpp>
