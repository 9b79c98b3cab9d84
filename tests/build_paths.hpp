#pragma once
// Where this build's `tilekit` binary and the source tree are: TILEKIT_BINARY and
// TILEKIT_SOURCE_DIR, each a C string. They are defined in build_paths.cpp, which the build writes
// (tests/CMakeLists.txt), and not passed to every test file as compile definitions: the test
// sources then compile to the same objects in every checkout, so that ccache shares them between
// checkouts (CCACHE_BASEDIR, CMakeLists.txt) as it does the libraries'.
namespace tilekit::test {
const char* binary_path();  // the tilekit executable of this build
const char* source_dir();   // the source root
}  // namespace tilekit::test

#define TILEKIT_BINARY (::tilekit::test::binary_path())
#define TILEKIT_SOURCE_DIR (::tilekit::test::source_dir())
