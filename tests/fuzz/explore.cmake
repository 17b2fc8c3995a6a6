# cmake -DFUZZER=... -DSECONDS=n -DSEEDS=dir -DREGRESSIONS=dir -DDICT=file -DWORK=dir -P explore.cmake
# Open-ended fuzzing, by hand (cmake --build build --target fuzz-explore), never
# in CI: a random seed for SECONDS, from the seeds and what earlier
# explorations kept in WORK/explore. What it finds goes into the source tree,
# for committing: inputs that reach new code are merged into the seed corpus
# (SEEDS, which CI replays), and a crashing input is written to REGRESSIONS
# (which CI replays too, so it fails until the bug is fixed).
if(NOT EXISTS ${FUZZER})
    message(FATAL_ERROR "${FUZZER} was not built (is clang++ installed?)")
endif()
file(MAKE_DIRECTORY ${WORK}/explore ${REGRESSIONS})
execute_process(COMMAND ${FUZZER} -seed=0 -max_total_time=${SECONDS} -timeout=10 -rss_limit_mb=2048 -dict=${DICT}
                        -print_final_stats=1 -artifact_prefix=${REGRESSIONS}/ ${WORK}/explore ${SEEDS}
                RESULT_VARIABLE found)
# Only the inputs that add coverage to the seeds join them.
execute_process(COMMAND ${FUZZER} -merge=1 -timeout=10 -rss_limit_mb=2048 ${SEEDS} ${WORK}/explore
                RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
    message(FATAL_ERROR "merging into ${SEEDS} failed (see above)")
endif()
if(NOT found EQUAL 0)
    message(FATAL_ERROR "the fuzzer found a failing input and wrote it to ${REGRESSIONS}/: "
                        "fix the bug, then commit the input (renamed to say what it is)")
endif()
