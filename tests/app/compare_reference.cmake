# Asserts that `ddafem scene-reference` reproduces the committed reference exactly.
#
#   cmake -DDDAFEM=path/to/ddafem -DREFERENCE=docs/scene_reference.md -P compare_reference.cmake
execute_process(COMMAND "${DDAFEM}" scene-reference RESULT_VARIABLE exit_code
                OUTPUT_VARIABLE generated ERROR_VARIABLE err)
if(NOT exit_code STREQUAL "0")
  message(FATAL_ERROR "ddafem scene-reference failed (${exit_code}): ${err}")
endif()
file(READ "${REFERENCE}" committed)
if(NOT generated STREQUAL committed)
  message(FATAL_ERROR "${REFERENCE} is stale: it differs from the output of "
                      "`ddafem scene-reference`. Regenerate it with\n"
                      "  build/ddafem scene-reference > docs/scene_reference.md")
endif()
