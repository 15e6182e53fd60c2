# ctest simd_path: runs hesai_simd_path (tests/simd_path.cpp) with the paths the core must choose,
# so that a plain `ctest` checks them, not only .ci/run and .ci/cross.
#   cmake -DSIMD_PATH=<exe> [-DEMULATOR=<cmd;args>] [-DEXPECT=<simd;crc32;sha256>] -DEXPECT_PATHS=<.ci/expect-paths>
#         -P simd_path.cmake
# Where any HESAI_EXPECT_* variable is in the environment (.ci/run and .ci/cross export all three,
# "" for a path not checked), the environment decides, as before. Otherwise a cross build (EXPECT,
# from the toolchain: tests/CMakeLists.txt) expects what its target has, and a native one what
# .ci/expect-paths derives from this machine's /proc/cpuinfo, read now (the build machine's CPU
# may not be the one the tests run on).
cmake_minimum_required(VERSION 3.25)
set(names HESAI_EXPECT_SIMD HESAI_EXPECT_CRC32 HESAI_EXPECT_SHA256)
set(from_environment FALSE)
foreach(name IN LISTS names)
  if(DEFINED ENV{${name}})
    set(from_environment TRUE)
  endif()
endforeach()
if(from_environment)
  message(STATUS "expected paths: from the environment")
elseif(DEFINED EXPECT AND NOT EXPECT STREQUAL "")
  foreach(name value IN ZIP_LISTS names EXPECT)
    set(ENV{${name}} "${value}")
  endforeach()
  message(STATUS "expected paths: the cross target's (${EXPECT})")
else()
  execute_process(COMMAND bash "${EXPECT_PATHS}" RESULT_VARIABLE status OUTPUT_VARIABLE lines ERROR_VARIABLE why)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "simd_path: ${EXPECT_PATHS} failed (exit ${status}): ${why}"
                        "set HESAI_EXPECT_SIMD, HESAI_EXPECT_CRC32 and HESAI_EXPECT_SHA256 by hand on this machine")
  endif()
  string(REPLACE "\n" ";" lines "${lines}")
  set(seen 0)
  foreach(line IN LISTS lines)
    if(line MATCHES "^(HESAI_EXPECT_SIMD|HESAI_EXPECT_CRC32|HESAI_EXPECT_SHA256)=(.*)$")
      set(ENV{${CMAKE_MATCH_1}} "${CMAKE_MATCH_2}")
      math(EXPR seen "${seen} + 1")
    elseif(NOT line STREQUAL "")
      message(FATAL_ERROR "simd_path: unexpected line from ${EXPECT_PATHS}: ${line}")
    endif()
  endforeach()
  if(NOT seen EQUAL 3)
    message(FATAL_ERROR "simd_path: ${EXPECT_PATHS} printed ${seen} of its three lines")
  endif()
  message(STATUS "expected paths: from /proc/cpuinfo (.ci/expect-paths)")
endif()
execute_process(COMMAND ${EMULATOR} "${SIMD_PATH}" RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "simd_path: the core's paths are not the expected ones (exit ${status})")
endif()
