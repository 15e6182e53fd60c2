# hesai_discover_tests(TARGET [TEST_PREFIX PREFIX]): the GoogleTest cases of TARGET as ctests
# (label "unit").
#
# Natively, one ctest a case (gtest_discover_tests). Where the tests run under an emulator
# (CMAKE_CROSSCOMPILING_EMULATOR: the cross presets, under qemu-user), one ctest a suite,
# PREFIX + "Suite.*", running `TARGET --gtest_filter=Suite.*`: qemu-user spends about 0.12 s of
# CPU translating the test program's start-up before each process's first test, which one process
# a case paid 600 times a preset (docs/TESTING.md, "One process a suite under qemu"). Each suite
# writes GoogleTest's XML report to <build>/gtest-xml/PREFIX + Suite.xml ('/' as '_'), from which
# .ci/check-skips lists every skipped case by its own name, as it does natively from ctest's JUnit.
# The test presets' name filters see "Suite.*" where they saw "Suite.Case", so `^Suite\.` still
# selects it.
#
# HESAI_TESTS_BY_SUITE (cache, default: on where there is an emulator) forces either way.
include(GoogleTest)
if(CMAKE_CROSSCOMPILING_EMULATOR)
  set(HESAI_TESTS_BY_SUITE_DEFAULT ON)
else()
  set(HESAI_TESTS_BY_SUITE_DEFAULT OFF)
endif()
set(HESAI_TESTS_BY_SUITE ${HESAI_TESTS_BY_SUITE_DEFAULT} CACHE BOOL
    "One ctest per GoogleTest suite (default: on under an emulator), not one per case")

function(hesai_discover_tests target)
  cmake_parse_arguments(arg "" "TEST_PREFIX" "" ${ARGN})
  if(NOT HESAI_TESTS_BY_SUITE)
    gtest_discover_tests(${target} TEST_PREFIX "${arg_TEST_PREFIX}" DISCOVERY_TIMEOUT 120 PROPERTIES LABELS "unit")
    return()
  endif()
  # The suites are listed when the target is built (the program runs under the emulator then, as
  # gtest_discover_tests does), into a file ctest includes; until then, one test that says so.
  set(suites_file "${CMAKE_CURRENT_BINARY_DIR}/${target}_suites.cmake")
  set(include_file "${CMAKE_CURRENT_BINARY_DIR}/${target}_suites_include.cmake")
  # The emulator's words joined by '|': a ';' would split the argument of the command below.
  list(JOIN CMAKE_CROSSCOMPILING_EMULATOR "|" emulator)
  add_custom_command(TARGET ${target} POST_BUILD
    COMMAND ${CMAKE_COMMAND} "-DEXE=$<TARGET_FILE:${target}>" "-DEMULATOR=${emulator}"
            "-DPREFIX=${arg_TEST_PREFIX}" "-DXML_DIR=${PROJECT_BINARY_DIR}/gtest-xml"
            "-DWORKING_DIRECTORY=${CMAKE_CURRENT_BINARY_DIR}" "-DOUT=${suites_file}"
            -P ${PROJECT_SOURCE_DIR}/cmake/HesaiGtestSuitesList.cmake
    BYPRODUCTS ${suites_file}
    VERBATIM)
  file(WRITE "${include_file}"
       "if(EXISTS \"${suites_file}\")\n  include(\"${suites_file}\")\nelse()\n"
       "  add_test(${target}_NOT_BUILT ${target}_NOT_BUILT)\nendif()\n")
  set_property(DIRECTORY APPEND PROPERTY TEST_INCLUDE_FILES "${include_file}")
endfunction()
