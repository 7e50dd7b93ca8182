# Runs accelviz under a virtual X display to take a screenshot, then checks the PNG.
#   cmake -DXVFB_RUN=... -DVIEWER=... -DCHECKER=... -DOUTPUT=x.png -DWIDTH=640 -DHEIGHT=360
#         [-DEXTRA_ARGS=a|b|c] -P run_screenshot.cmake
# EXTRA_ARGS ("|"-separated: a scene, --no-ui, ...) go before --screenshot.
# A 24-bit screen: xvfb-run's default depth 8 may offer no RGB visual for an OpenGL context.
file(REMOVE "${OUTPUT}")
string(REPLACE "|" ";" extra_args "${EXTRA_ARGS}")
execute_process(
  COMMAND "${XVFB_RUN}" -a -s "-screen 0 1920x1080x24"
          "${VIEWER}" ${extra_args} --screenshot "${OUTPUT}" --size "${WIDTH}x${HEIGHT}"
  RESULT_VARIABLE viewer_result
  OUTPUT_VARIABLE viewer_out
  ERROR_VARIABLE viewer_err
  TIMEOUT 120)
if(NOT viewer_result EQUAL 0)
  message(FATAL_ERROR "accelviz --screenshot exited with '${viewer_result}'\n${viewer_out}${viewer_err}")
endif()
if(NOT EXISTS "${OUTPUT}")
  message(FATAL_ERROR "accelviz exited 0 but wrote no ${OUTPUT}\n${viewer_out}${viewer_err}")
endif()
execute_process(
  COMMAND "${CHECKER}" "${OUTPUT}" "${WIDTH}" "${HEIGHT}"
  RESULT_VARIABLE check_result)
if(NOT check_result EQUAL 0)
  message(FATAL_ERROR "png_check failed on ${OUTPUT}")
endif()
