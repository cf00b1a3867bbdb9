// The single Catch2 main shared by every test executable (Catch2 v2 from Debian bookworm).
#define CATCH_CONFIG_MAIN
#include <catch2/catch.hpp>
