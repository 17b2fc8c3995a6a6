# Every kernel also runs under Oclgrind, a second OpenCL implementation: a
# simulator that reports out-of-bounds and uninitialised accesses and data
# races, which PoCL and GPU drivers let pass silently. Tiny images keep each
# entry to seconds. Options:
#   --check-api      OpenCL API misuse by the host (bad arguments, sizes);
#   --data-races     work-group and global memory races;
#   --uninitialized  reads of uninitialised memory; Oclgrind 21.10 cannot
#                    interpret LLVM's freeze instruction, which the optimiser
#                    emits, so these entries compile with -cl-opt-disable.
# A kernel build cache would hide the compile from the simulator: off.
find_program(OCLGRIND oclgrind)
set(OCLGRIND_CHECK ${CMAKE_CURRENT_SOURCE_DIR}/kernels/oclgrind_check.cmake)
set(OCLGRIND_DATA ${CMAKE_CURRENT_SOURCE_DIR}/kernels/data)
set(OCLGRIND_LOGS ${CMAKE_BINARY_DIR}/oclgrind-logs)
file(MAKE_DIRECTORY ${OCLGRIND_LOGS})
set(OCLGRIND_BASIC --check-api --data-races)
set(OCLGRIND_STRICT ${OCLGRIND_BASIC} --uninitialized --build-options -cl-opt-disable)

add_executable(probe_kernels_check ${CMAKE_CURRENT_SOURCE_DIR}/kernels/probe_kernels_check.cpp)
target_link_libraries(probe_kernels_check PRIVATE clpath_test_support GTest::gtest)
target_compile_definitions(probe_kernels_check PRIVATE CLPATH_TEST_KERNEL_DATA="${OCLGRIND_DATA}")

# clpath_oclgrind_test(name OUTPUT regex [REPORT regex] OPTIONS ... COMMAND ...)
function(clpath_oclgrind_test name)
    cmake_parse_arguments(T "" "OUTPUT;REPORT" "OPTIONS;COMMAND" ${ARGN})
    if(OCLGRIND)
        add_test(NAME oclgrind.${name}
                 COMMAND ${CMAKE_COMMAND} -DOCLGRIND=${OCLGRIND} -DLOG=${OCLGRIND_LOGS}/${name}.log
                         "-DOPTIONS=${T_OPTIONS}" "-DCMD=${T_COMMAND}" "-DEXPECT_OUTPUT=${T_OUTPUT}"
                         "-DEXPECT_REPORT=${T_REPORT}" -P ${OCLGRIND_CHECK})
    else()
        # Not skipped in silence: tools/install-deps.sh installs it.
        add_test(NAME oclgrind.${name} COMMAND ${CMAKE_COMMAND} -E echo "oclgrind is not installed")
        set_tests_properties(oclgrind.${name} PROPERTIES WILL_FAIL TRUE)
    endif()
    set_tests_properties(oclgrind.${name} PROPERTIES ENVIRONMENT "CLPATH_CACHE_DIR=off" TIMEOUT 120 LABELS oclgrind)
endfunction()

# The renderer: each integrator with every material and light feature compiled
# in, on a scene that has them all (every material kind, triangle, point, spot
# and directional lights, an environment image, smooth normals).
# Without --uninitialized: Oclgrind 21.10 does not count memory set by
# clEnqueueFillBuffer (how the film is cleared) as initialised, and reports
# every read of the film's running sums.
set(OCLGRIND_SCENE ${OCLGRIND_DATA}/oclgrind-features.json)
foreach(integrator path path-bsdf ao normals depth albedo heatmap)
    clpath_oclgrind_test(render.${integrator} OPTIONS ${OCLGRIND_BASIC}
                         COMMAND $<TARGET_FILE:clpath> render ${OCLGRIND_SCENE} --all-features -i ${integrator}
                                 -q -o ${OCLGRIND_LOGS}/render-${integrator}.pfm
                         OUTPUT "device=\"Oclgrind Simulator\" .*integrator=${integrator} .*nonfinite=0")
endforeach()
# The wavefront kernels (both light-transport integrators, every feature), with
# the races between their work-items' queue appends checked.
foreach(integrator path path-bsdf)
    clpath_oclgrind_test(render.wavefront.${integrator} OPTIONS ${OCLGRIND_BASIC}
                         COMMAND $<TARGET_FILE:clpath> render ${OCLGRIND_SCENE} --all-features -i ${integrator}
                                 --kernel wavefront -q -o ${OCLGRIND_LOGS}/render-wavefront-${integrator}.pfm
                         OUTPUT "device=\"Oclgrind Simulator\" .*integrator=${integrator} .*nonfinite=0 .*kernel=wavefront")
endforeach()
# Programs compiled with only the features a scene has, the flat object list,
# uniform hemisphere sampling with the depth roulette rule.
clpath_oclgrind_test(render.scene_features OPTIONS ${OCLGRIND_BASIC}
                     COMMAND $<TARGET_FILE:clpath> render ${OCLGRIND_SCENE} -q -o ${OCLGRIND_LOGS}/render-scene.pfm
                     OUTPUT "nonfinite=0")
clpath_oclgrind_test(render.flat OPTIONS ${OCLGRIND_BASIC}
                     COMMAND $<TARGET_FILE:clpath> render ${OCLGRIND_SCENE} --accel flat -q
                             -o ${OCLGRIND_LOGS}/render-flat.pfm
                     OUTPUT "nonfinite=0 accel=flat")
clpath_oclgrind_test(render.cornell_uniform_depth_rr OPTIONS ${OCLGRIND_BASIC}
                     COMMAND $<TARGET_FILE:clpath> render cornell --width 5 --height 3 --spp 2 --hemisphere uniform
                             --rr depth -q -o ${OCLGRIND_LOGS}/render-cornell.pfm
                     OUTPUT "triangles=196 .*nonfinite=0")
# The ray-batch kernels (clpath bench rays), through the BVH and the flat list.
clpath_oclgrind_test(bench_rays.bvh OPTIONS ${OCLGRIND_STRICT}
                     COMMAND $<TARGET_FILE:clpath> bench rays ${OCLGRIND_SCENE} --width 4 --height 4 --launches 1
                     OUTPUT "primary: 256 rays .* 0 mismatched.*shadow: .* 0 mismatched.*diffuse: .* 0 mismatched")
clpath_oclgrind_test(bench_rays.flat OPTIONS ${OCLGRIND_BASIC}
                     COMMAND $<TARGET_FILE:clpath> bench rays ${OCLGRIND_SCENE} --width 4 --height 4 --launches 1
                             --accel flat
                     OUTPUT "primary: 256 rays .* 0 mismatched.*shadow: .* 0 mismatched.*diffuse: .* 0 mismatched")
# The test probes.
clpath_oclgrind_test(probes OPTIONS ${OCLGRIND_STRICT} COMMAND $<TARGET_FILE:probe_kernels_check>
                     OUTPUT "\\[  PASSED  \\] 9 tests")
# The controls: a kernel that writes past its buffer's end, and one that
# stores an uninitialised value, must be reported ...
clpath_oclgrind_test(control_reports_out_of_bounds OPTIONS ${OCLGRIND_BASIC}
                     COMMAND $<TARGET_FILE:probe_kernels_check> --gtest_also_run_disabled_tests
                             --gtest_filter=OclgrindControl.DISABLED_WritePastTheEnd
                     OUTPUT "." REPORT "Invalid write of size 4 at global memory address")
clpath_oclgrind_test(control_reports_uninitialised OPTIONS ${OCLGRIND_STRICT}
                     COMMAND $<TARGET_FILE:probe_kernels_check> --gtest_also_run_disabled_tests
                             --gtest_filter=OclgrindControl.DISABLED_StoreUninitialised
                     OUTPUT "." REPORT "Uninitialized value written to global memory")
# ... and the same run checked as every other entry is must fail, on the
# report (not on any failure: a run that did not reach Oclgrind fails too).
clpath_oclgrind_test(control_fails_the_check OPTIONS ${OCLGRIND_BASIC}
                     COMMAND $<TARGET_FILE:probe_kernels_check> --gtest_also_run_disabled_tests
                             --gtest_filter=OclgrindControl.DISABLED_WritePastTheEnd
                     OUTPUT "\\[  PASSED  \\] 1 test")
if(OCLGRIND)
    set_tests_properties(oclgrind.control_fails_the_check PROPERTIES PASS_REGULAR_EXPRESSION
                         "Oclgrind reported:[ \n]+Invalid write of size 4 at global memory address")
endif()
