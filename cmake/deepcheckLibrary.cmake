# deepcheck_add_library(<name> [EXPORT <set>] SOURCES <file>...)
#
# One deepcheck library: target deepcheck_<name> (file libdeepcheck_<name>), alias and exported
# name deepcheck::<name>, C++17 for its users, the folder's include/ as its public headers (from
# the source tree when building, from <prefix>/include when installed), shared-library version
# and a run path to its sibling libraries. With DEEPCHECK_INSTALL the library joins the export
# set (deepcheckTargets unless EXPORT names another) and its headers are installed.
function(deepcheck_add_library name)
  cmake_parse_arguments(arg "" "EXPORT" "SOURCES" ${ARGN})
  if(NOT arg_EXPORT)
    set(arg_EXPORT deepcheckTargets)
  endif()
  set(target deepcheck_${name})
  add_library(${target} ${arg_SOURCES})
  add_library(deepcheck::${name} ALIAS ${target})
  set_target_properties(${target} PROPERTIES
    EXPORT_NAME ${name}
    VERSION ${PROJECT_VERSION}
    SOVERSION ${PROJECT_VERSION_MAJOR}.${PROJECT_VERSION_MINOR}
    INSTALL_RPATH "$ORIGIN")
  target_compile_features(${target} PUBLIC cxx_std_17)
  # Eigen and the standard headers most sources include, parsed once per library instead of once
  # per source: a library of several sources compiles in about three quarters of the time. Every
  # source includes what it uses all the same; the sanitizer stage's ThreadSanitizer build compiles
  # geometry, robots and checker with CMAKE_DISABLE_PRECOMPILE_HEADERS=ON to keep that true.
  list(LENGTH arg_SOURCES num_sources)
  if(num_sources GREATER 3)
    target_precompile_headers(${target} PRIVATE
      <Eigen/Core> <Eigen/Geometry> <algorithm> <cmath> <map> <sstream> <stdexcept> <string> <vector>)
  endif()
  set(include_dir ${CMAKE_CURRENT_SOURCE_DIR}/include)
  if(EXISTS ${include_dir})
    target_include_directories(${target} PUBLIC
      $<BUILD_INTERFACE:${include_dir}>
      $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  endif()
  if(DEEPCHECK_INSTALL)
    install(TARGETS ${target} EXPORT ${arg_EXPORT}
      ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
      LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
      RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
    if(EXISTS ${include_dir})
      install(DIRECTORY ${include_dir}/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} FILES_MATCHING PATTERN "*.h")
    endif()
  endif()
endfunction()
