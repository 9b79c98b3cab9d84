# tilekit_library(NAME DEPS...): one static library per top-level folder, built from every
# *.cpp in that folder (an interface library while the folder has headers only).
# Headers are included as "folder/file.hpp": from the source root in the build tree, and from
# include/tilekit/ of an install prefix (cmake/install.cmake). The archive is libtilekit_NAME.a,
# so that installed libraries do not clash with other projects' libbase.a or libimage.a.
function(tilekit_library name)
  file(GLOB sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/*.cpp)
  if(sources)
    add_library(${name} STATIC ${sources})
    tilekit_library_paths(${name} PUBLIC)
    target_link_libraries(${name} PUBLIC ${ARGN})
  else()
    add_library(${name} INTERFACE)
    tilekit_library_paths(${name} INTERFACE)
    target_link_libraries(${name} INTERFACE ${ARGN})
  endif()
endfunction()

# The include paths and archive name above, for a library made by add_library (tilesets/).
function(tilekit_library_paths name scope)
  target_include_directories(${name} ${scope} $<BUILD_INTERFACE:${CMAKE_SOURCE_DIR}>
                                              $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}/tilekit>)
  if(NOT scope STREQUAL INTERFACE)
    set_target_properties(${name} PROPERTIES OUTPUT_NAME tilekit_${name})
  endif()
endfunction()
