# hesai_writers: point-cloud output (CSV, PCD, PLY, bird's-eye PNG). Hosted C++17, no third-party
# libraries. Included from port/CMakeLists.txt.
add_library(hesai_writers STATIC
  ${CMAKE_CURRENT_LIST_DIR}/src/writers.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/birdseye.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/png.cpp)
add_library(hesai::writers ALIAS hesai_writers)
target_compile_features(hesai_writers PUBLIC cxx_std_17)
target_include_directories(hesai_writers PUBLIC ${CMAKE_CURRENT_LIST_DIR}/include)
target_link_libraries(hesai_writers PUBLIC hesai::core PRIVATE hesai_warnings)
