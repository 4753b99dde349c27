# Runs `ddafem DDAFEM_COMMAND SCENE [--set SET]` (DDAFEM_COMMAND defaults to check; `run` writes into a
# scratch directory) and asserts exit code 2 and an error on stderr that
# matches EXPECT, or, without EXPECT, the regex on the scene's first line `# expect: REGEX`
# (CMake regex syntax).
#
#   cmake -DDDAFEM=path/to/ddafem -DSCENE=scene.yaml [-DDDAFEM_COMMAND=run] [-DSET=key=value]
#         [-DEXPECT=REGEX]
#         -P expect_exit.cmake
if(DEFINED EXPECT)
  set(regex "${EXPECT}")
else()
  file(READ "${SCENE}" text LIMIT 4096)
  string(REGEX MATCH "^# expect: ([^\n]*)" first_line "${text}")
  if(NOT first_line)
    message(FATAL_ERROR "${SCENE}: the first line must be '# expect: REGEX'")
  endif()
  set(regex "${CMAKE_MATCH_1}")
endif()

if(NOT DEFINED DDAFEM_COMMAND)
  set(DDAFEM_COMMAND check)
endif()
set(command "${DDAFEM}" ${DDAFEM_COMMAND} "${SCENE}")
if(DDAFEM_COMMAND STREQUAL "run")
  list(APPEND command -o "${CMAKE_CURRENT_BINARY_DIR}/expect_exit_run" --quiet)
endif()
if(DEFINED SET)
  list(APPEND command --set "${SET}")
endif()
execute_process(COMMAND ${command} RESULT_VARIABLE exit_code OUTPUT_VARIABLE out
                ERROR_VARIABLE err)
message(STATUS "exit code: ${exit_code}\nstderr: ${err}")
if(NOT exit_code STREQUAL "2")
  message(FATAL_ERROR "expected exit code 2, got '${exit_code}'\nstdout: ${out}")
endif()
if(NOT err MATCHES "${regex}")
  message(FATAL_ERROR "stderr does not match\n  ${regex}")
endif()
