// The translation unit that builds the test suites' precompiled header
// (contact2d_test_pch, tests/CMakeLists.txt): CMake compiles the header for
// a target that has at least one source, and this is that source.
