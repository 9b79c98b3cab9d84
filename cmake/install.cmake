# Installation (`cmake --install build --prefix DIR`), the CMake package that
# `find_package(Tilekit)` reads, and the Debian packages of `cpack -G DEB` (README "Install").
#
# Two components, one Debian package each:
#   runtime  bin/tilekit and the documentation                              -> tilekit
#   dev      headers, static libraries, TilekitConfig.cmake, the consumer example -> libtilekit-dev
# Reference tile sets and stored packings (tilesets/data/) are compiled into the tilesets library
# (cmake/embed_data.cmake), so neither the binary nor a program linking the libraries reads a data
# file at run time: an installed prefix works wherever it is copied.
include(CMakePackageConfigHelpers)

# The libraries a program needs to look up packings (atlas, packing), tile (tiling), store and
# query results (results) and check aperiodic sets or make point sets, with every library they
# link. texture/ and render/ are left out: render's GLSL renderer links the system's EGL
# privately, which a static export would have to name by absolute path.
set(TILEKIT_INSTALLED_LIBRARIES base image tilesets tiling solver results checkpoints packing aperiodic atlas points)
set(TILEKIT_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/Tilekit)

install(TARGETS tilekit RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT runtime)
install(FILES README.md BENCHMARKS.md docs/TESTING.md DESTINATION ${CMAKE_INSTALL_DOCDIR} COMPONENT runtime)
install(DIRECTORY docs/images DESTINATION ${CMAKE_INSTALL_DOCDIR} COMPONENT runtime)
# The tile sets with a known status (aperiodic/data/: periodic, finite, hard; their sources in its
# README), which the README's `aperiodic verify` examples read: share/tilekit/aperiodic/data.
install(DIRECTORY aperiodic/data/ DESTINATION ${CMAKE_INSTALL_DATADIR}/tilekit/aperiodic/data COMPONENT runtime
        FILES_MATCHING PATTERN "*.tiles" PATTERN "README.md")

install(TARGETS ${TILEKIT_INSTALLED_LIBRARIES} EXPORT TilekitTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT dev)
foreach(lib ${TILEKIT_INSTALLED_LIBRARIES})
  file(GLOB headers ${CMAKE_SOURCE_DIR}/${lib}/*.hpp)
  install(FILES ${headers} DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/tilekit/${lib} COMPONENT dev)
endforeach()
install(EXPORT TilekitTargets NAMESPACE Tilekit:: DESTINATION ${TILEKIT_CMAKE_DIR} COMPONENT dev)
configure_package_config_file(cmake/TilekitConfig.cmake.in ${CMAKE_BINARY_DIR}/TilekitConfig.cmake
                              INSTALL_DESTINATION ${TILEKIT_CMAKE_DIR})
# Before 1.0 a minor release may change the libraries' interface: 0.1 accepts 0.1.x only.
write_basic_package_version_file(${CMAKE_BINARY_DIR}/TilekitConfigVersion.cmake COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_BINARY_DIR}/TilekitConfig.cmake ${CMAKE_BINARY_DIR}/TilekitConfigVersion.cmake
        DESTINATION ${TILEKIT_CMAKE_DIR} COMPONENT dev)
install(DIRECTORY examples/consumer DESTINATION ${CMAKE_INSTALL_DOCDIR}/examples COMPONENT dev)

# Debian packages: `cpack -G DEB --config build/CPackConfig.cmake`. The runtime package's
# dependencies are the Debian packages of the shared libraries the binary links, as
# dpkg-shlibdeps finds them (Debian: dpkg-dev).
set(CPACK_PACKAGE_NAME tilekit)
set(CPACK_PACKAGE_VENDOR Tilekit)
set(CPACK_PACKAGE_CONTACT "Tilekit developers")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY
    "Wang and corner tiles: tile packings, stochastic tilings, texture atlases, aperiodic tile sets")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_COMPONENTS_ALL runtime dev)
set(CPACK_DEB_COMPONENT_INSTALL ON)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_RUNTIME_PACKAGE_NAME tilekit)
set(CPACK_DEBIAN_RUNTIME_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_DEV_PACKAGE_NAME libtilekit-dev)
set(CPACK_DEBIAN_DEV_PACKAGE_SECTION libdevel)
# What TilekitConfig.cmake finds (OpenMP comes with the compiler: libgomp).
set(CPACK_DEBIAN_DEV_PACKAGE_DEPENDS
    "libboost-dev (>= 1.74), libsqlite3-dev, libfmt-dev, nlohmann-json3-dev, libtiff-dev, libopenexr-dev")
include(CPack)
