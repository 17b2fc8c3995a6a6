# Runs a command under Oclgrind and fails on any diagnostic it writes:
#   cmake -DOCLGRIND=path -DLOG=file "-DOPTIONS=--data-races;..." "-DCMD=prog;args" -DEXPECT_OUTPUT=regex
#         [-DEXPECT_REPORT=regex] -P oclgrind_check.cmake
# EXPECT_OUTPUT must match the command's output, and say that the Oclgrind
# device ran it (not a real device found beside it). With EXPECT_REPORT (the
# control), the log must instead hold a diagnostic matching it.
file(REMOVE "${LOG}")
execute_process(COMMAND ${OCLGRIND} --log ${LOG} ${OPTIONS} ${CMD} RESULT_VARIABLE rc OUTPUT_VARIABLE out
                ERROR_VARIABLE err)
set(all "${out}${err}")
set(log "")
if(EXISTS "${LOG}")
    file(READ "${LOG}" log)
endif()
message("${all}")
if(NOT all MATCHES "Oclgrind")
    message(FATAL_ERROR "the command did not run on the Oclgrind device")
endif()
if(DEFINED EXPECT_REPORT AND NOT EXPECT_REPORT STREQUAL "")
    if(NOT log MATCHES "${EXPECT_REPORT}")
        message(FATAL_ERROR "Oclgrind did not report '${EXPECT_REPORT}'; its log:\n${log}")
    endif()
    message("Oclgrind reported, as it must:\n${log}")
    return()
endif()
if(NOT log STREQUAL "")
    message(FATAL_ERROR "Oclgrind reported:\n${log}")
endif()
if(NOT rc EQUAL 0)
    message(FATAL_ERROR "exit status ${rc}")
endif()
if(NOT all MATCHES "${EXPECT_OUTPUT}")
    message(FATAL_ERROR "output does not match '${EXPECT_OUTPUT}'")
endif()
