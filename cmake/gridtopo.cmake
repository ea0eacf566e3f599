# Helpers shared by every gridtopo library, app and test.

set(GRIDTOPO_WARNINGS -Wall -Wextra -Wpedantic -Wno-psabi)

# gridtopo_library(<name> SOURCES ... DEPS ...): libs/<name> -> target gridtopo_<name>, alias gridtopo::<name>.
function(gridtopo_library name)
  cmake_parse_arguments(A "" "" "SOURCES;DEPS" ${ARGN})
  add_library(gridtopo_${name} ${A_SOURCES})
  add_library(gridtopo::${name} ALIAS gridtopo_${name})
  target_include_directories(gridtopo_${name} PUBLIC ${CMAKE_CURRENT_SOURCE_DIR}/include)
  target_compile_options(gridtopo_${name} PRIVATE ${GRIDTOPO_WARNINGS})
  target_link_libraries(gridtopo_${name} PUBLIC ${A_DEPS})
  set_target_properties(gridtopo_${name} PROPERTIES POSITION_INDEPENDENT_CODE ON)
endfunction()

# gridtopo_app(<exe-name> SOURCES ... DEPS ...)
function(gridtopo_app name)
  cmake_parse_arguments(A "" "" "SOURCES;DEPS" ${ARGN})
  add_executable(${name} ${A_SOURCES})
  target_compile_options(${name} PRIVATE ${GRIDTOPO_WARNINGS})
  target_link_libraries(${name} PRIVATE ${A_DEPS})
endfunction()

# gridtopo_test(<name> SOURCES ... DEPS ... [LABELS ...]): a GoogleTest binary registered with CTest.
# Tests find bundled data through the GRIDTOPO_DATA_DIR define and the app binaries through GRIDTOPO_BIN_DIR.
function(gridtopo_test name)
  cmake_parse_arguments(A "" "" "SOURCES;DEPS;LABELS" ${ARGN})
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
  gtest_discover_tests(${name} DISCOVERY_TIMEOUT 120 PROPERTIES LABELS "${A_LABELS}")
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
