// The translation unit that builds the test suites' shared precompiled
// header (tnv_test_pch in tests/CMakeLists.txt); it has no code of its own.
