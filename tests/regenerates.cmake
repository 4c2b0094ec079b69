# Runs SCRIPT to write OUT and fails unless OUT equals COMMITTED byte for byte.
execute_process(COMMAND python3 ${SCRIPT} ${OUT} RESULT_VARIABLE rc OUTPUT_QUIET)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${SCRIPT} failed (${rc})")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${OUT} ${COMMITTED} RESULT_VARIABLE differ)
if(differ)
  message(FATAL_ERROR "${COMMITTED} differs from what ${SCRIPT} writes: run the script and commit its output")
endif()
