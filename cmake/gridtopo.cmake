# Helpers shared by every gridtopo library, app and test.

set(GRIDTOPO_WARNINGS -Wall -Wextra -Wpedantic -Wno-psabi)

include(GNUInstallDirs)

# The libraries a program outside the tree links (issue 37): shared, installed with their headers and exported as
# gridtopo::<name> by find_package(gridtopo) (cmake/gridtopoConfig.cmake.in). The others (eval, experiment,
# session, sim, simtrain) serve our apps and tests only: static, linked into the apps, never installed.
# Shared because MRPT, OpenCV and Ceres are shared in Debian: a program and our apps then hold one copy of each
# library (and of MRPT's class registry), and a fix to one of ours reaches every program without relinking.
set(GRIDTOPO_PUBLIC_LIBRARIES core io_core io places topology slam_core slam mapping)

# gridtopo_library(<name> SOURCES ... DEPS ...): libs/<name> -> target gridtopo_<name>, alias gridtopo::<name>
# (the same name find_package(gridtopo) gives a program outside the tree).
function(gridtopo_library name)
  cmake_parse_arguments(A "" "" "SOURCES;DEPS" ${ARGN})
  if(name IN_LIST GRIDTOPO_PUBLIC_LIBRARIES)
    set(_type SHARED)
  else()
    set(_type STATIC)
  endif()
  add_library(gridtopo_${name} ${_type} ${A_SOURCES})
  add_library(gridtopo::${name} ALIAS gridtopo_${name})
  target_include_directories(gridtopo_${name} PUBLIC $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>
                                                     $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_compile_options(gridtopo_${name} PRIVATE ${GRIDTOPO_WARNINGS})
  target_link_libraries(gridtopo_${name} PUBLIC ${A_DEPS})
  set_target_properties(gridtopo_${name} PROPERTIES POSITION_INDEPENDENT_CODE ON)
  if(_type STREQUAL SHARED)
    set_target_properties(gridtopo_${name} PROPERTIES EXPORT_NAME ${name} VERSION ${PROJECT_VERSION}
                          SOVERSION ${PROJECT_VERSION_MAJOR}.${PROJECT_VERSION_MINOR})
    install(TARGETS gridtopo_${name} EXPORT gridtopoTargets
            LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT runtime NAMELINK_COMPONENT dev)
    install(DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR}/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} COMPONENT dev)
  endif()
endfunction()

# gridtopo_app(<exe-name> SOURCES ... DEPS ...): installed to bin/ (CMAKE_INSTALL_BINDIR).
function(gridtopo_app name)
  cmake_parse_arguments(A "" "" "SOURCES;DEPS" ${ARGN})
  add_executable(${name} ${A_SOURCES})
  target_compile_options(${name} PRIVATE ${GRIDTOPO_WARNINGS})
  target_link_libraries(${name} PRIVATE ${A_DEPS})
  install(TARGETS ${name} RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT runtime)
endfunction()

# gridtopo_test(<name> SOURCES ... DEPS ... [LABELS ...] [RESOURCE_LOCK name]): a GoogleTest binary registered with
# CTest; its tests never run beside others holding the same RESOURCE_LOCK.
# Tests find bundled data through the GRIDTOPO_DATA_DIR define and the app binaries through GRIDTOPO_BIN_DIR.
function(gridtopo_test name)
  cmake_parse_arguments(A "" "RESOURCE_LOCK" "SOURCES;DEPS;LABELS" ${ARGN})
  add_executable(${name} ${A_SOURCES})
  target_compile_options(${name} PRIVATE ${GRIDTOPO_WARNINGS})
  target_link_libraries(${name} PRIVATE ${A_DEPS} GTest::gtest GTest::gtest_main)
  target_include_directories(${name} PRIVATE ${CMAKE_SOURCE_DIR}/tests)  # tests/common/*.h
  target_compile_definitions(${name} PRIVATE
    GRIDTOPO_DATA_DIR="${CMAKE_SOURCE_DIR}/datasets"
    GRIDTOPO_SOURCE_DIR="${CMAKE_SOURCE_DIR}"
    GRIDTOPO_BIN_DIR="${CMAKE_BINARY_DIR}/bin")
  if(NOT A_LABELS)
    set(A_LABELS unit)
  endif()
  if(A_RESOURCE_LOCK)
    # Tests that share something only one may use at a time (the GUI tests' `xvfb-run -a`: two started at once can
    # pick the same display number, and one fails at once) never run together under `ctest -j`.
    gtest_discover_tests(${name} DISCOVERY_TIMEOUT 120 PROPERTIES LABELS "${A_LABELS}" RESOURCE_LOCK "${A_RESOURCE_LOCK}")
  else()
    gtest_discover_tests(${name} DISCOVERY_TIMEOUT 120 PROPERTIES LABELS "${A_LABELS}")
  endif()
endfunction()

# gridtopo_tests_in_dir(DEPS ... [LABELS ...]): one test binary per *_test.cpp file of the current directory.
function(gridtopo_tests_in_dir)
  cmake_parse_arguments(A "" "" "DEPS;LABELS" ${ARGN})
  file(GLOB _srcs CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/*_test.cpp)
  foreach(src ${_srcs})
    get_filename_component(_name ${src} NAME_WE)
    gridtopo_test(${_name} SOURCES ${src} DEPS ${A_DEPS} LABELS ${A_LABELS})
  endforeach()
endfunction()
