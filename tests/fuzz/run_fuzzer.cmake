# cmake -DFUZZER=... -DSEEDS=dir -DREGRESSIONS=dir -DDICT=file -DWORK=dir -DSEED=n -DRUNS=n
#       [-DUNAVAILABLE=reason -DHINT=text] -P run_fuzzer.cmake
# What CI runs: the same result on every run of one checkout. Every kept crash
# input and every seed input must run cleanly, then a short fuzz whose seed
# and number of runs are fixed explores from the seeds. Open-ended random
# fuzzing is explore.cmake's (the fuzz-explore target), never a test's.
# The build makes the fuzzers (the clpath_fuzzers target); a test only runs one.
if(UNAVAILABLE)
    message(FATAL_ERROR "clpath-fuzz: the fuzz targets could not be built: ${UNAVAILABLE} (${HINT})")
endif()
if(NOT EXISTS ${FUZZER})
    message(FATAL_ERROR "clpath-fuzz: ${FUZZER} was not built: build the default target "
                        "(cmake --build build) or clpath_fuzzers")
endif()
foreach(kind regressions seeds)
    if(kind STREQUAL "regressions")
        file(GLOB inputs ${REGRESSIONS}/*)
        set(what "a kept crash input fails again")
    else()
        file(GLOB inputs ${SEEDS}/*)
        set(what "a seed input fails")
    endif()
    if(inputs)
        execute_process(COMMAND ${FUZZER} -timeout=10 -rss_limit_mb=2048 ${inputs} RESULT_VARIABLE rc)
        if(NOT rc EQUAL 0)
            message(FATAL_ERROR "${what} (see above)")
        endif()
    endif()
endforeach()
# A fresh copy of the seeds each time: libFuzzer adds what it finds to its
# first corpus folder, and a corpus left from an earlier run would change
# what this run explores. -reload=0: libFuzzer otherwise re-reads that folder
# every second, which makes the inputs it explores depend on timing; with it,
# two runs of one seed explore the same inputs. A crash is written to
# WORK/crash-* for keeping in regressions/.
file(REMOVE_RECURSE ${WORK}/corpus)
file(MAKE_DIRECTORY ${WORK}/corpus)
file(GLOB seeds ${SEEDS}/*)
file(COPY ${seeds} DESTINATION ${WORK}/corpus)
execute_process(COMMAND ${FUZZER} -seed=${SEED} -runs=${RUNS} -reload=0 -timeout=10 -rss_limit_mb=2048 -dict=${DICT}
                        -print_final_stats=1 -artifact_prefix=${WORK}/ ${WORK}/corpus
                RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
    message(FATAL_ERROR "the fuzzer found a failing input; it is in ${WORK}/ (crash-*, timeout-*, oom-*)")
endif()
