# Fails when the freestanding core references any symbol it would need a hosted library for.
# Usage: cmake -DNM=nm -DLIB=libhesai_core_freestanding.a -P check_freestanding.cmake
execute_process(COMMAND ${NM} -u ${LIB} OUTPUT_VARIABLE out RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "nm failed on ${LIB}")
endif()
# Symbols one member of the archive takes from another are not external: collect the defined ones.
execute_process(COMMAND ${NM} -g --defined-only ${LIB} OUTPUT_VARIABLE defined_out RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "nm --defined-only failed on ${LIB}")
endif()
string(REGEX MATCHALL "[^ \n]+\n" defined "${defined_out}")
list(TRANSFORM defined STRIP)
string(REPLACE "\n" ";" lines "${out}")
set(bad "")
set(count 0)
foreach(line IN LISTS lines)
  string(STRIP "${line}" line)
  if(line STREQUAL "" OR line MATCHES ":$")
    continue()  # blank lines and "member.o:" headings
  endif()
  string(REGEX REPLACE "^U +" "" sym "${line}")
  list(FIND defined "${sym}" at)
  if(NOT at EQUAL -1)
    continue()  # defined by another member of the core
  endif()
  math(EXPR count "${count} + 1")
  # Allowed: the four memory functions, compiler helpers and the stack protector.
  if(sym MATCHES "^(memcpy|memmove|memset|memcmp)$" OR sym MATCHES "^__(aeabi|gcc|builtin|stack_chk|udiv|umod|div|mod|ashl|lshr|popcount|clz|ctz|x86\\.)"
     OR sym MATCHES "^_GLOBAL_OFFSET_TABLE_$")
    continue()
  endif()
  list(APPEND bad "${sym}")
endforeach()
if(bad)
  list(REMOVE_DUPLICATES bad)
  message(FATAL_ERROR "core is not freestanding; it references: ${bad}")
endif()
message(STATUS "freestanding: ${count} undefined references, all allowed")
