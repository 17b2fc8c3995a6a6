# cmake -DFUZZER=... -DSECONDS=60 -DSEEDS=dir -DREGRESSIONS=dir -DDICT=file -DWORK=dir -P run_fuzzer.cmake
if(NOT EXISTS ${FUZZER})
    message("clpath-fuzz: skipped: ${FUZZER} was not built")
    return()
endif()
# Inputs that once crashed a target: each must now run cleanly.
file(GLOB kept ${REGRESSIONS}/*)
if(kept)
    execute_process(COMMAND ${FUZZER} ${kept} RESULT_VARIABLE rc)
    if(NOT rc EQUAL 0)
        message(FATAL_ERROR "a kept crash input fails again (see above)")
    endif()
endif()
# New inputs go to a working corpus in the build folder, never into the source tree;
# a crash is written to WORK/crash-* for keeping in regressions/.
file(MAKE_DIRECTORY ${WORK}/corpus)
execute_process(COMMAND ${FUZZER} -max_total_time=${SECONDS} -timeout=10 -rss_limit_mb=2048 -dict=${DICT}
                        -print_final_stats=1 -artifact_prefix=${WORK}/ ${WORK}/corpus ${SEEDS}
                RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
    message(FATAL_ERROR "the fuzzer found a failing input; it is in ${WORK}/ (crash-*, timeout-*, oom-*)")
endif()
