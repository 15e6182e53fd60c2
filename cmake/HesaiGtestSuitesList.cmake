# cmake -P HesaiGtestSuitesList.cmake, run after a test program is built (HesaiGtestSuites.cmake):
# lists the program's GoogleTest suites (`EXE --gtest_list_tests`, through EMULATOR: its words
# joined by '|') and writes OUT, the ctest file with one test a suite:
#   PREFIX + "Suite.*"   EMULATOR EXE --gtest_filter=Suite.* --gtest_output=xml:XML_DIR/<name>.xml
# <name> is PREFIX + Suite with '/' as '_' (a parameterised suite is "Instance/Suite").
foreach(var EXE OUT XML_DIR WORKING_DIRECTORY)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "HesaiGtestSuitesList.cmake: ${var} not set")
  endif()
endforeach()
string(REPLACE "|" ";" emulator "${EMULATOR}")
execute_process(COMMAND ${emulator} "${EXE}" --gtest_list_tests
                OUTPUT_VARIABLE listing ERROR_VARIABLE errors RESULT_VARIABLE status TIMEOUT 120)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "${EXE} --gtest_list_tests failed (${status}):\n${errors}")
endif()

set(command "")
foreach(word IN LISTS emulator)
  string(APPEND command "[==[${word}]==] ")
endforeach()
string(APPEND command "[==[${EXE}]==]")

set(tests "")
set(suites 0)
set(suite "")
# A suite's ctest COST (ctest starts the costliest first when it has no timings of its own yet, as
# on a fresh clone): its number of cases, written once the next suite's line (or the end) is read.
macro(close_suite)
  if(suite)
    string(APPEND tests "set_tests_properties([==[${name}]==] PROPERTIES COST ${cases})\n")
  endif()
endmacro()
# One list item a line. Only the suites' names are kept, which hold no ';', '[' or ']': those
# characters (in a case's "# GetParam() = ..." comment) are dropped first, as a ';' would split a
# line and a '[' would join the lines up to its ']' in a CMake list.
string(REGEX REPLACE "[][;]" "" listing "${listing}")
string(REPLACE "\n" ";" lines "${listing}")
foreach(line IN LISTS lines)
  # A suite's line starts in the first column and ends with '.', before any "  # TypeParam = ..."
  # comment; its cases' lines are indented.
  if(line MATCHES "^([^ #][^ ]*)\\.( .*)?$")
    close_suite()
    set(suite "${CMAKE_MATCH_1}")
    set(cases 0)
    set(name "${PREFIX}${suite}.*")
    string(REPLACE "/" "_" xml "${PREFIX}${suite}")
    string(APPEND tests
           "add_test([==[${name}]==] ${command} [==[--gtest_filter=${suite}.*]==] "
           "[==[--gtest_output=xml:${XML_DIR}/${xml}.xml]==])\n"
           "set_tests_properties([==[${name}]==] PROPERTIES LABELS unit WORKING_DIRECTORY [==[${WORKING_DIRECTORY}]==])\n")
    math(EXPR suites "${suites} + 1")
  elseif(suite AND line MATCHES "^  [^ ]")
    math(EXPR cases "${cases} + 1")
  endif()
endforeach()
close_suite()
if(suites EQUAL 0)
  message(FATAL_ERROR "${EXE} --gtest_list_tests listed no suite:\n${listing}")
endif()
file(MAKE_DIRECTORY "${XML_DIR}")
file(WRITE "${OUT}" "${tests}")
