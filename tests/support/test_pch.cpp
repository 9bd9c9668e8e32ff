// The translation unit that owns the test areas' shared precompiled header
// (tests/CMakeLists.txt: fts_test_pch); it has nothing of its own.
