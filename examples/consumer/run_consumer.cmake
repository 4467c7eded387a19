# The consumer test (tests/CMakeLists.txt): builds this folder's project against deepcheck and runs
# it. cmake -DMODE=<mode> -DSOURCE_DIR=<deepcheck source> -DBUILD_DIR=<deepcheck build>
#       -DWORK_DIR=<scratch folder> -DGENERATOR=<generator> -P run_consumer.cmake
#   MODE=find_package      installs BUILD_DIR into WORK_DIR/prefix (cmake --install), checks that
#                          the installed package names neither SOURCE_DIR nor BUILD_DIR, and builds
#                          the consumer with CMAKE_PREFIX_PATH=WORK_DIR/prefix; the program reads
#                          the installed share/deepcheck.
#   MODE=add_subdirectory  builds the consumer with DEEPCHECK_SOURCE_TREE=SOURCE_DIR (deepcheck's
#                          libraries rebuilt in WORK_DIR: only those the consumer links).
# Both use ccache when it is installed, and pass when the program prints a positive minimum
# clearance.
cmake_minimum_required(VERSION 3.21)

function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "failed (${status}): ${ARGN}\n${out}")
  endif()
  set(output "${out}" PARENT_SCOPE)
endfunction()

file(REMOVE_RECURSE ${WORK_DIR})
set(args -S ${CMAKE_CURRENT_LIST_DIR} -B ${WORK_DIR}/build -G ${GENERATOR} -DCMAKE_BUILD_TYPE=Release)
find_program(CCACHE ccache)
if(CCACHE)
  list(APPEND args -DCMAKE_CXX_COMPILER_LAUNCHER=${CCACHE})
endif()

if(MODE STREQUAL "find_package")
  set(prefix ${WORK_DIR}/prefix)
  run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})
  file(GLOB_RECURSE package_files ${prefix}/*.cmake ${prefix}/*.pc)
  foreach(file IN LISTS package_files)
    file(READ ${file} text)
    foreach(dir ${SOURCE_DIR} ${BUILD_DIR})
      string(FIND "${text}" "${dir}" at)
      if(NOT at EQUAL -1)
        message(FATAL_ERROR "${file} names ${dir}: the installed package must not depend on the build machine's folders")
      endif()
    endforeach()
  endforeach()
  # pkg-config users: deepcheck.pc names the installed headers and libraries.
  find_program(PKG_CONFIG pkg-config)
  if(PKG_CONFIG)
    file(GLOB_RECURSE pc_file ${prefix}/deepcheck.pc)
    get_filename_component(pc_dir "${pc_file}" DIRECTORY)
    set(ENV{PKG_CONFIG_PATH} "${pc_dir}")
    run(${PKG_CONFIG} --cflags --libs deepcheck)
    if(NOT output MATCHES "-I[^ ]*/include" OR NOT output MATCHES "-ldeepcheck_planners")
      message(FATAL_ERROR "pkg-config --cflags --libs deepcheck: ${output}")
    endif()
  endif()
  list(APPEND args -DCMAKE_PREFIX_PATH=${prefix})
elseif(MODE STREQUAL "add_subdirectory")
  list(APPEND args -DDEEPCHECK_SOURCE_TREE=${SOURCE_DIR})
else()
  message(FATAL_ERROR "MODE must be find_package or add_subdirectory, not '${MODE}'")
endif()

run(${CMAKE_COMMAND} ${args})
run(${CMAKE_COMMAND} --build ${WORK_DIR}/build)

run(${WORK_DIR}/build/deepcheck_consumer)
message(STATUS "${output}")
if(NOT output MATCHES "min clearance +(0\\.0*[1-9][0-9]*|[1-9][0-9]*\\.[0-9]+) m")
  message(FATAL_ERROR "the consumer printed no positive minimum clearance:\n${output}")
endif()
