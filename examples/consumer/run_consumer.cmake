# The consumer test (tests/CMakeLists.txt): builds this folder's project against deepcheck and runs
# it. cmake -DMODE=<mode> -DSOURCE_DIR=<deepcheck source> -DBUILD_DIR=<deepcheck build>
#       -DWORK_DIR=<scratch folder> -DGENERATOR=<generator> -DCXX=<C++ compiler> -P run_consumer.cmake
#   MODE=find_package      installs BUILD_DIR (static libraries, the default) into WORK_DIR/prefix
#                          (cmake --install), checks that the installed package names neither
#                          SOURCE_DIR nor BUILD_DIR, builds main.cpp with the compiler flags
#                          `pkg-config --cflags --libs deepcheck` gives and runs it, then builds the
#                          consumer with CMAKE_PREFIX_PATH=WORK_DIR/prefix; the programs read the
#                          installed share/deepcheck.
#   MODE=add_subdirectory  builds the consumer with DEEPCHECK_SOURCE_TREE=SOURCE_DIR and
#                          BUILD_SHARED_LIBS=ON (deepcheck's libraries rebuilt in WORK_DIR, shared)
#                          and runs it; then builds the rest of deepcheck's libraries there, installs
#                          them (cmake --install of the deepcheck subfolder, whose install rules are
#                          the top-level project's) and checks that shared package as find_package
#                          does the static one. One rebuild of the libraries tests both ways.
# All use ccache when it is installed, and pass when every program built prints a positive minimum
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
set(args -S ${CMAKE_CURRENT_LIST_DIR} -G ${GENERATOR} -DCMAKE_BUILD_TYPE=Release)
find_program(CCACHE ccache)
if(CCACHE)
  list(APPEND args -DCMAKE_CXX_COMPILER_LAUNCHER=${CCACHE})
endif()

# check_clearance(<output>): fails unless the consumer's output has a positive minimum clearance.
function(check_clearance output)
  if(NOT output MATCHES "min clearance +(0\\.0*[1-9][0-9]*|[1-9][0-9]*\\.[0-9]+) m")
    message(FATAL_ERROR "the consumer printed no positive minimum clearance:\n${output}")
  endif()
endfunction()

# check_installed(<prefix>): no file of the installed package names the source or build folder.
function(check_installed prefix)
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
endfunction()

# pkg_config_consumer(<prefix>): main.cpp compiled and linked with pkg-config's flags alone, then
# run on the installed data (the installed libraries found through LD_LIBRARY_PATH when shared).
function(pkg_config_consumer prefix)
  find_program(PKG_CONFIG pkg-config REQUIRED)
  file(GLOB_RECURSE pc_file ${prefix}/deepcheck.pc)
  get_filename_component(pc_dir "${pc_file}" DIRECTORY)
  set(ENV{PKG_CONFIG_PATH} "${pc_dir}")
  run(${PKG_CONFIG} --cflags --libs deepcheck)
  string(STRIP "${output}" flags)
  separate_arguments(flags UNIX_COMMAND "${flags}")
  run(${PKG_CONFIG} --variable=datadir deepcheck)
  string(STRIP "${output}" data)
  set(program ${WORK_DIR}/consumer_pkg_config)
  run(${CXX} -O1 "-DCONSUMER_DATA_DIR=\"${data}\"" -o ${program} ${CMAKE_CURRENT_LIST_DIR}/main.cpp ${flags})
  get_filename_component(libdir "${pc_dir}" DIRECTORY)
  run(${CMAKE_COMMAND} -E env "LD_LIBRARY_PATH=${libdir}" ${program} ${data})
  message(STATUS "pkg-config consumer: ${output}")
  check_clearance("${output}")
endfunction()

# consume_installed(<prefix> <build folder>): the package installed in <prefix> checked, used
# through pkg-config, and through find_package by the consumer built in <build folder> and run.
function(consume_installed prefix build)
  check_installed(${prefix})
  pkg_config_consumer(${prefix})
  build_and_run(${build} -DCMAKE_PREFIX_PATH=${prefix})
endfunction()

# build_and_run(<build folder> <configure arguments>...): the consumer configured, built and run.
function(build_and_run build)
  run(${CMAKE_COMMAND} ${args} -B ${build} ${ARGN})
  run(${CMAKE_COMMAND} --build ${build})
  run(${build}/deepcheck_consumer)
  message(STATUS "${output}")
  check_clearance("${output}")
endfunction()

if(MODE STREQUAL "find_package")
  run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${WORK_DIR}/prefix)
  consume_installed(${WORK_DIR}/prefix ${WORK_DIR}/build)
elseif(MODE STREQUAL "add_subdirectory")
  set(build ${WORK_DIR}/build)
  build_and_run(${build} -DDEEPCHECK_SOURCE_TREE=${SOURCE_DIR} -DBUILD_SHARED_LIBS=ON -DDEEPCHECK_INSTALL=ON)
  # The consumer built only the libraries it links; the install needs them all: the deepcheck
  # folder's "all" (a target of the top folder with Ninja, its own Makefile with make).
  if(GENERATOR MATCHES "Ninja")
    run(${CMAKE_COMMAND} --build ${build} --target deepcheck/all)
  else()
    run(${CMAKE_COMMAND} --build ${build}/deepcheck)
  endif()
  run(${CMAKE_COMMAND} --install ${build}/deepcheck --prefix ${WORK_DIR}/prefix)
  consume_installed(${WORK_DIR}/prefix ${WORK_DIR}/build_installed)
else()
  message(FATAL_ERROR "MODE must be find_package or add_subdirectory, not '${MODE}'")
endif()
