# Helpers shared by every CMakeLists.txt of the project.
include_guard(GLOBAL)

find_program(HI_CCACHE ccache)
if(HI_CCACHE)
  set(CMAKE_CXX_COMPILER_LAUNCHER ${HI_CCACHE})
  set(CMAKE_C_COMPILER_LAUNCHER ${HI_CCACHE})
endif()

# Warnings and sanitizer flags for project targets only (third-party headers are SYSTEM).
function(hi_set_target_options target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wno-deprecated-declarations)
  if(HI_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
  # Debian's hardening of linked programs and plugins (dpkg-buildflags;
  # lintian's hardening-no-relro and hardening-no-bindnow).
  target_link_options(${target} PRIVATE -Wl,-z,relro -Wl,-z,now)
  if(HI_SANITIZE OR HI_FUZZ)
    # HI_FUZZ adds libFuzzer's coverage instrumentation (fuzzer-no-link: the
    # libFuzzer runtime and its main() only go into the harnesses, see
    # hi_add_fuzzer). GCC's -Wmaybe-uninitialized gives false positives under
    # the sanitizers' instrumentation (std::regex, std::function moves in
    # libstdc++ 12); clang has no such warning.
    set(sanitizers address,undefined)
    if(HI_FUZZ)
      set(sanitizers fuzzer-no-link,address,undefined)
    endif()
    target_compile_options(${target} PRIVATE -fsanitize=${sanitizers} -fno-omit-frame-pointer
                                             -fno-sanitize-recover=undefined)
    if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
      target_compile_options(${target} PRIVATE -Wno-maybe-uninitialized)
    endif()
    target_link_options(${target} PRIVATE -fsanitize=address,undefined)
  endif()
endfunction()

# hi_add_fuzzer(name SOURCES ... DEPS ... [DEFINITIONS ...]): a libFuzzer
# harness (tests/fuzz), built only with HI_FUZZ; linked with
# -fsanitize=fuzzer so libFuzzer provides main().
function(hi_add_fuzzer name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS;DEFINITIONS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_DEPS})
  target_compile_definitions(${name} PRIVATE ${ARG_DEFINITIONS})
  hi_set_target_options(${name})
  target_link_options(${name} PRIVATE -fsanitize=fuzzer,address,undefined)
  set_target_properties(${name} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${PROJECT_BINARY_DIR}/fuzz)
endfunction()

# hi_add_library(name SOURCES ... [PUBLIC_DEPS ...] [PRIVATE_DEPS ...])
# One target per core module, named hull_<module>; headers are included as
# "<module>/<file>.h" from core/.
function(hi_add_library name)
  cmake_parse_arguments(ARG "" "" "SOURCES;PUBLIC_DEPS;PRIVATE_DEPS" ${ARGN})
  add_library(${name} STATIC ${ARG_SOURCES})
  target_include_directories(${name} PUBLIC ${PROJECT_SOURCE_DIR}/core)
  target_link_libraries(${name} PUBLIC ${ARG_PUBLIC_DEPS} PRIVATE ${ARG_PRIVATE_DEPS})
  hi_set_target_options(${name})
endfunction()

# hi_add_test(name SOURCES ... DEPS ... [LABELS label] [TIMEOUT s]); LABELS default to "core".
# Give one label (gtest_discover_tests cannot pass a list through): ctest
# matches labels as regular expressions, so "core-integration" is selected by
# -L core and left out by -LE integration (the sanitizer run's selection).
# A GoogleTest executable registered with CTest (one CTest entry per test case).
function(hi_add_test name)
  cmake_parse_arguments(ARG "WHOLE" "TIMEOUT" "SOURCES;DEPS;LABELS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_DEPS} GTest::gtest GTest::gmock GTest::gtest_main)
  target_compile_definitions(${name} PRIVATE
    HI_SHARED_DATA_DIR="${HI_SHARED_DATA_DIR}"
    HI_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    HI_BINARY_DIR="${PROJECT_BINARY_DIR}")
  hi_set_target_options(${name})
  if(NOT ARG_TIMEOUT)
    set(ARG_TIMEOUT 600)
  endif()
  if(NOT ARG_LABELS)
    set(ARG_LABELS core)  # core tests also run in the sanitizer build
  endif()
  if(ARG_WHOLE)
    # One ctest for the whole program: its tests share expensive fixtures
    # (whole simulated adjustments) in one process instead of recomputing
    # them in a process per test.
    add_test(NAME ${name} COMMAND ${name})
    set_tests_properties(${name} PROPERTIES LABELS "${ARG_LABELS}" TIMEOUT ${ARG_TIMEOUT})
    return()
  endif()
  include(GoogleTest)
  gtest_discover_tests(${name}
    DISCOVERY_TIMEOUT 60
    PROPERTIES LABELS "${ARG_LABELS}" TIMEOUT ${ARG_TIMEOUT})
endfunction()
