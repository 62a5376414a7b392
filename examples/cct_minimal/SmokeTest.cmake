# Runs cct_minimal at 48x48 for 3 frames into a fresh directory; fails unless
# it exits 0, writes its PNG and reports a hit rate above 0 for the last frame.
# Usage: cmake -DPROGRAM=<cct_minimal> -DWORK_DIR=<dir> -P SmokeTest.cmake
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")
execute_process(COMMAND "${PROGRAM}" 48 48 3 "${WORK_DIR}/last.png"
                RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE errors)
message("${output}${errors}")
if(NOT result EQUAL 0)
  message(FATAL_ERROR "cct_minimal exited with ${result}")
endif()
if(NOT EXISTS "${WORK_DIR}/last.png")
  message(FATAL_ERROR "cct_minimal wrote no image")
endif()
if(NOT output MATCHES "frame 3/3 lookups [0-9]+ hits [0-9]+ hit_rate ([0-9.]+)")
  message(FATAL_ERROR "no parseable line for the last frame")
endif()
if(NOT CMAKE_MATCH_1 GREATER 0)
  message(FATAL_ERROR "last frame's hit rate is ${CMAKE_MATCH_1}, expected > 0")
endif()
file(REMOVE_RECURSE "${WORK_DIR}")
