# deepcheck::ompl: OMPL as an imported target, made from the variables OMPL's CMake config sets
# (OMPL_INCLUDE_DIRS, OMPL_LIBRARIES; the config exports no target). Included by the build and
# again by deepcheckConfig.cmake after find_dependency(ompl), so the exported deepcheck::planners
# names this target and no path of the machine that built deepcheck is written into the package.
#
# OMPL's include list also names /usr/include, which must not become a -isystem directory (it
# breaks #include_next in the C++ standard headers). The rest are system directories, as the
# include directories of every imported target (OMPL's headers are not -Wextra clean).
if(NOT TARGET deepcheck::ompl)
  set(_deepcheck_ompl_includes ${OMPL_INCLUDE_DIRS})
  list(REMOVE_ITEM _deepcheck_ompl_includes /usr/include /usr/local/include)
  add_library(deepcheck::ompl INTERFACE IMPORTED)
  set_target_properties(deepcheck::ompl PROPERTIES
    INTERFACE_INCLUDE_DIRECTORIES "${_deepcheck_ompl_includes}"
    INTERFACE_LINK_LIBRARIES "${OMPL_LIBRARIES}")
  unset(_deepcheck_ompl_includes)
endif()
