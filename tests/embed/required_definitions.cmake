# For the embed scripts run with `cmake -D... -P`: stops with one line naming the first of the
# given variables the command line did not define.
#   require_definitions(<script name> <variable>...)
function(require_definitions script)
  foreach(v ${ARGN})
    if(NOT DEFINED ${v})
      message(FATAL_ERROR "${script}: -D${v}= is required")
    endif()
  endforeach()
endfunction()
