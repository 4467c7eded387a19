# The installed CMake package (deepcheckConfig.cmake, its version file, the exported targets
# deepcheck::<library>) and deepcheck.pc for pkg-config. Included by the top-level CMakeLists.txt
# when DEEPCHECK_INSTALL is on, after every library is defined.
include(CMakePackageConfigHelpers)

set(DEEPCHECK_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/deepcheck)
set(DEEPCHECK_INSTALL_DATADIR ${CMAKE_INSTALL_DATADIR}/deepcheck)
if(BUILD_SHARED_LIBS)
  set(DEEPCHECK_SHARED_LIBS ON)
else()
  set(DEEPCHECK_SHARED_LIBS OFF)
endif()

install(EXPORT deepcheckTargets NAMESPACE deepcheck:: DESTINATION ${DEEPCHECK_INSTALL_CMAKEDIR})
if(TARGET deepcheck_fcl_reference)
  install(EXPORT deepcheckFclReferenceTargets NAMESPACE deepcheck:: DESTINATION ${DEEPCHECK_INSTALL_CMAKEDIR})
endif()

configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/deepcheckConfig.cmake.in
  ${PROJECT_BINARY_DIR}/deepcheckConfig.cmake
  INSTALL_DESTINATION ${DEEPCHECK_INSTALL_CMAKEDIR}
  PATH_VARS DEEPCHECK_INSTALL_DATADIR)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/deepcheckConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES
  ${PROJECT_BINARY_DIR}/deepcheckConfig.cmake
  ${PROJECT_BINARY_DIR}/deepcheckConfigVersion.cmake
  ${CMAKE_CURRENT_LIST_DIR}/deepcheckOmpl.cmake
  DESTINATION ${DEEPCHECK_INSTALL_CMAKEDIR})

# deepcheck.pc finds its prefix from its own location, so the installed tree can be moved.
file(RELATIVE_PATH DEEPCHECK_PC_TO_PREFIX /prefix/${CMAKE_INSTALL_LIBDIR}/pkgconfig /prefix)
# The libraries deepcheck's own link privately: a static install needs them on the consumer's link
# line (Requires), a shared one does not (Requires.private).
set(_deepcheck_pc_private "qhull_r urdfdom tinyxml assimp yaml-cpp")
if(BUILD_SHARED_LIBS)
  set(DEEPCHECK_PC_REQUIRES "")
  set(DEEPCHECK_PC_REQUIRES_PRIVATE "${_deepcheck_pc_private}")
else()
  set(DEEPCHECK_PC_REQUIRES " ${_deepcheck_pc_private}")
  set(DEEPCHECK_PC_REQUIRES_PRIVATE "")
endif()
# OMPL by its include folders and libraries rather than `Requires: ompl`: ompl.pc's Cflags carry
# -std=c++14, which would come after ours and compile deepcheck's C++17 headers as C++14.
set(DEEPCHECK_PC_OMPL_CFLAGS "")
foreach(dir IN LISTS OMPL_INCLUDE_DIRS)
  if(NOT dir MATCHES "^/usr(/local)?/include/?$")
    string(APPEND DEEPCHECK_PC_OMPL_CFLAGS " -I${dir}")
  endif()
endforeach()
list(JOIN OMPL_LIBRARIES " " DEEPCHECK_PC_OMPL_LIBS)
configure_file(${CMAKE_CURRENT_LIST_DIR}/deepcheck.pc.in ${PROJECT_BINARY_DIR}/deepcheck.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/deepcheck.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
