# Rendering over several devices and MPI ranks, and interrupted renders: the
# image is the same bits however the work was shared, and bad use fails cleanly.
set(SCALE_OUT ${CMAKE_BINARY_DIR}/scale-out-test)
file(MAKE_DIRECTORY ${SCALE_OUT})
# PoCL shows two CPU devices of one thread each.
set(TWO_POCL_DEVICES "POCL_DEVICES=pthread pthread;POCL_MAX_PTHREAD_COUNT=1")
set(SMALL render --spp 12 --chunk 2 --width 40 --height 32 --seed 9 -q)
string(REPLACE ";" " " SMALL_ARGS "${SMALL}")

function(clpath_same_image_test name cmds outs env)
    add_test(NAME cli.scale.${name}
             COMMAND ${CMAKE_COMMAND} "-DCMDS=${cmds}" "-DOUTS=${outs}" -P ${CMAKE_CURRENT_SOURCE_DIR}/cli/same_image.cmake)
    set_tests_properties(cli.scale.${name} PROPERTIES ENVIRONMENT "${CLPATH_TEST_ENV};${env}" TIMEOUT 300)
endfunction()

set(C $<TARGET_FILE:clpath>)
# Like clpath_cli_test, for a command that is not clpath itself (mpirun).
function(clpath_command_test name)
    cmake_parse_arguments(T "FAIL" "OUTPUT;FORBID" "CMD" ${ARGN})
    add_test(NAME cli.scale.${name}
             COMMAND ${CMAKE_COMMAND} "-DCMD=${T_CMD}" -DEXPECT_FAIL=${T_FAIL} "-DEXPECT_OUTPUT=${T_OUTPUT}"
                     -DFORBID_FILE=${T_FORBID} -P ${CMAKE_CURRENT_SOURCE_DIR}/cli/expect.cmake)
    set_tests_properties(cli.scale.${name} PROPERTIES ENVIRONMENT "${CLPATH_TEST_ENV}" TIMEOUT 300)
endfunction()
clpath_same_image_test(two_devices_same_bits
    "${C} ${SMALL_ARGS} --device 0 -o ${SCALE_OUT}/one.pfm|${C} ${SMALL_ARGS} --device all -o ${SCALE_OUT}/all.pfm|${C} ${SMALL_ARGS} --device 1,0 -o ${SCALE_OUT}/list.pfm"
    "${SCALE_OUT}/one.pfm;${SCALE_OUT}/all.pfm;${SCALE_OUT}/list.pfm" "${TWO_POCL_DEVICES}")

# Adaptive sampling decides between passes from the exact film, so the pixels
# that stop, their counts and the image are the same over two devices as on
# one, in both kernel shapes.
set(ADAPTIVE render --spp 256 --chunk 4 --width 40 --height 32 --seed 9 -q --noise-target 0.1)
string(REPLACE ";" " " ADAPTIVE_ARGS "${ADAPTIVE}")
foreach(shape mega wavefront)
    set(A "${C} ${ADAPTIVE_ARGS} --kernel ${shape}")
    set(D ${SCALE_OUT}/adaptive-${shape})
    clpath_same_image_test(adaptive_${shape}_two_devices_same_bits
        "${A} --device 0 -o ${D}-one.pfm|${A} --device all -o ${D}-all.pfm|${A} --device 1,0 -o ${D}-list.pfm"
        "${D}-one.pfm;${D}-all.pfm;${D}-list.pfm" "${TWO_POCL_DEVICES}")
    clpath_same_image_test(adaptive_${shape}_two_devices_same_counts
        "${A} --device 0 -o ${D}-c1.pfm --sample-count-image ${D}-n1.pfm|${A} --device all -o ${D}-c2.pfm --sample-count-image ${D}-n2.pfm"
        "${D}-n1.pfm;${D}-n2.pfm" "${TWO_POCL_DEVICES}")
endforeach()

clpath_cli_test(scale_device_twice FAIL ARGS render --spp 1 --device 0,0 -o ${SCALE_OUT}/twice.pfm
                OUTPUT "device \\[0\\].*named twice" FORBID ${SCALE_OUT}/twice.pfm)
clpath_cli_test(scale_device_missing_in_list FAIL ARGS render --spp 1 --device 0,9 -o ${SCALE_OUT}/missing.pfm
                OUTPUT "9: no device with that index" FORBID ${SCALE_OUT}/missing.pfm)
clpath_cli_test(scale_resume_missing FAIL ARGS render --spp 4 --resume ${SCALE_OUT}/no.ckpt -o ${SCALE_OUT}/r.pfm
                OUTPUT "--resume .*no\\.ckpt: no such file" FORBID ${SCALE_OUT}/r.pfm)

# The checkpoint's folder is checked before anything renders (it used to fail at the first save).
clpath_usage_test(checkpoint_folder_missing RC 2 ARGS render --spp 4 --checkpoint 1
                  --checkpoint-file ${SCALE_OUT}/no/such/folder/c.ckpt -o ${SCALE_OUT}/cf.pfm FORBID ${SCALE_OUT}/cf.pfm
                  OUTPUT "clpath: error: --checkpoint-file .*/no/such/folder/c\\.ckpt: folder .*/no/such/folder does not exist"
                  REJECT "rendering 'cornell'")
clpath_usage_test(checkpoint_file_is_folder RC 2 ARGS render --spp 4 --checkpoint 1 --checkpoint-file ${SCALE_OUT}
                  -o ${SCALE_OUT}/cf-folder.pfm FORBID ${SCALE_OUT}/cf-folder.pfm
                  OUTPUT "clpath: error: --checkpoint-file .*scale-out-test: is a folder \\(name a file in it\\)")

add_test(NAME cli.scale.interrupt_checkpoint_resume
         COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/cli/interrupt_resume.sh $<TARGET_FILE:clpath> ${SCALE_OUT}/interrupt)
set_tests_properties(cli.scale.interrupt_checkpoint_resume PROPERTIES ENVIRONMENT "${CLPATH_TEST_ENV}" TIMEOUT 600)

if(CLPATH_WITH_MPI)
    # Open MPI refuses root without these, and CI runs as root; two ranks on
    # one 2-core machine need --oversubscribe.
    set(MPIRUN ${MPIEXEC_EXECUTABLE} --allow-run-as-root --oversubscribe)
    string(REPLACE ";" " " MPIRUN_ARGS "${MPIRUN}")
    clpath_same_image_test(mpi_two_ranks_same_bits
        "${C} ${SMALL_ARGS} -o ${SCALE_OUT}/rank1.pfm|${MPIRUN_ARGS} -n 2 ${C} ${SMALL_ARGS} -o ${SCALE_OUT}/ranks2.pfm"
        "${SCALE_OUT}/rank1.pfm;${SCALE_OUT}/ranks2.pfm" "")
    # A rank with another scene, one that fails, one that dies: a clear error, no image.
    clpath_command_test(mpi_ranks_disagree FAIL OUTPUT "ranks disagree about the scene" FORBID ${SCALE_OUT}/disagree.pfm
        CMD ${MPIRUN} -n 1 ${C} ${SMALL} -o ${SCALE_OUT}/disagree.pfm : -n 1 ${C} ${SMALL} --max-depth 3 -o ${SCALE_OUT}/disagree.pfm)
    clpath_command_test(mpi_rank_fails FAIL OUTPUT "rank 1 .*9: no device with that index" FORBID ${SCALE_OUT}/fails.pfm
        CMD ${MPIRUN} -n 1 ${C} ${SMALL} -o ${SCALE_OUT}/fails.pfm : -n 1 ${C} ${SMALL} --device 9 -o ${SCALE_OUT}/fails.pfm)
    clpath_command_test(mpi_rank_dies FAIL OUTPUT "exited on signal 9" FORBID ${SCALE_OUT}/dies.pfm
        CMD ${MPIRUN} -n 1 ${C} render --spp 100000 --width 40 --height 32 -q -o ${SCALE_OUT}/dies.pfm
            : -n 1 ${CMAKE_CURRENT_SOURCE_DIR}/cli/dying_rank.sh)
    # Adaptive sampling over ranks: each takes a fixed share of every pass's
    # chunks and the ranks add their films at each boundary, so two ranks give
    # one process's image and sample counts, bit for bit.
    clpath_same_image_test(mpi_two_ranks_adaptive_same_bits
        "${C} ${ADAPTIVE_ARGS} -o ${SCALE_OUT}/adaptive-rank1.pfm --sample-count-image ${SCALE_OUT}/adaptive-rank1-n.pfm|${MPIRUN_ARGS} -n 2 ${C} ${ADAPTIVE_ARGS} -o ${SCALE_OUT}/adaptive-ranks2.pfm --sample-count-image ${SCALE_OUT}/adaptive-ranks2-n.pfm"
        "${SCALE_OUT}/adaptive-rank1.pfm;${SCALE_OUT}/adaptive-ranks2.pfm" "")
    clpath_same_image_test(mpi_two_ranks_adaptive_same_counts
        "${C} ${ADAPTIVE_ARGS} -o ${SCALE_OUT}/adaptive-rank1b.pfm --sample-count-image ${SCALE_OUT}/adaptive-rank1b-n.pfm|${MPIRUN_ARGS} -n 2 ${C} ${ADAPTIVE_ARGS} -o ${SCALE_OUT}/adaptive-ranks2b.pfm --sample-count-image ${SCALE_OUT}/adaptive-ranks2b-n.pfm"
        "${SCALE_OUT}/adaptive-rank1b-n.pfm;${SCALE_OUT}/adaptive-ranks2b-n.pfm" "")
    # With a time budget the ranks could end at different chunks of a pass: refused, clearly.
    clpath_command_test(mpi_noise_target_time_refused FAIL OUTPUT "--noise-target over MPI ranks needs --spp and no --time"
        FORBID ${SCALE_OUT}/adaptive-ranks-time.pfm
        CMD ${MPIRUN} -n 2 ${C} ${SMALL} --time 5 --noise-target 0.1 -o ${SCALE_OUT}/adaptive-ranks-time.pfm)
    # A convergence study over ranks: every configuration is measured once and reported by rank 0.
    clpath_command_test(mpi_bench_convergence
        OUTPUT "spread over 2 MPI ranks.*\\| thesis .*\\| cosine .*\\| no-rr .*\\| throughput-rr .*\\| nee-mis .*\\| bvh .*\\| clpath "
        CMD ${MPIRUN} -n 2 ${C} bench convergence ${CMAKE_SOURCE_DIR}/scenes/cornell-classic.json
            --reference ${CMAKE_SOURCE_DIR}/benchmarks/references/cornell-classic-cycles.exr --quick --max-spp 2)
endif()
