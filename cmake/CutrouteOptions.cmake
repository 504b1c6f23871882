# Warnings, sanitizers and the helper that registers one GoogleTest executable per module.

if(CUTROUTE_SANITIZE AND CMAKE_BUILD_TYPE STREQUAL "Release")
  message(FATAL_ERROR "CUTROUTE_SANITIZE wants a debug-info build: use -DCMAKE_BUILD_TYPE=RelWithDebInfo or Debug")
endif()
if(CUTROUTE_BUILD_BENCH AND CUTROUTE_SANITIZE)
  message(FATAL_ERROR "CUTROUTE_BUILD_BENCH and CUTROUTE_SANITIZE contradict each other: benchmarks under sanitizers measure nothing")
endif()

if(CUTROUTE_SANITIZE)
  # -O1 with line tables only: reports still name file and line, and the sanitized build takes half
  # the compile time of -O2 -g, which keeps `make test` (both builds) inside CI's 30 minutes.
  set(CMAKE_CXX_FLAGS_RELWITHDEBINFO "-O1 -g1 -DNDEBUG")
  set(CMAKE_CXX_FLAGS_DEBUG "-O1 -g1")
  # Applied to everything we compile (library, CLI, tests) so that the runtime sees every frame.
  add_compile_options(-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined)
  add_link_options(-fsanitize=address,undefined)
endif()

# Strict warnings on our own targets only; third-party headers come in as SYSTEM includes.
function(cutroute_set_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wconversion
                         -Wno-sign-conversion -Wnon-virtual-dtor -Wold-style-cast -Woverloaded-virtual)
  if(CUTROUTE_WARNINGS_AS_ERRORS)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()

# cutroute_add_test(NAME SOURCES a.cpp b.cpp): one GoogleTest executable registered with CTest.
function(cutroute_add_test name)
  cmake_parse_arguments(ARG "" "" "SOURCES" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE cutroute::cutroute cutroute_test_support GTest::gtest GTest::gmock GTest::gtest_main)
  cutroute_set_warnings(${name})
  # CTest names are the GoogleTest names; the label names the executable: `ctest -L solve_test`.
  gtest_discover_tests(${name} DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT 600 LABELS ${name})
endfunction()
