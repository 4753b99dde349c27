# Runs `ddafem ARGS...` (ARGS a ;-list) and asserts its exit code CODE and that its stdout and
# stderr together match EXPECT (CMake regex syntax).
#
#   cmake -DDDAFEM=path/to/ddafem "-DARGS=run;--bogus" -DCODE=2 "-DEXPECT=REGEX"
#         -P expect_command.cmake
execute_process(COMMAND "${DDAFEM}" ${ARGS} RESULT_VARIABLE exit_code OUTPUT_VARIABLE out
                ERROR_VARIABLE err)
if(NOT exit_code STREQUAL "${CODE}")
  message(FATAL_ERROR "ddafem ${ARGS}: exit code ${exit_code}, expected ${CODE}\n${out}${err}")
endif()
if(NOT "${out}${err}" MATCHES "${EXPECT}")
  message(FATAL_ERROR "ddafem ${ARGS}: the output does not match '${EXPECT}':\n${out}${err}")
endif()
