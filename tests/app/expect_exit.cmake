# Runs `ddafem check SCENE [--set SET]` and asserts exit code 2 and an error on stderr that
# matches EXPECT, or, without EXPECT, the regex on the scene's first line `# expect: REGEX`
# (CMake regex syntax).
#
#   cmake -DDDAFEM=path/to/ddafem -DSCENE=scene.yaml [-DSET=key=value] [-DEXPECT=REGEX]
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

set(command "${DDAFEM}" check "${SCENE}")
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
