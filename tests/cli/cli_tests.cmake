# Command-line tests of the clpath program: each runs it as a user would.
set(CLI_OUT ${CMAKE_BINARY_DIR}/cli-test-out)
file(MAKE_DIRECTORY ${CLI_OUT})

function(clpath_cli_test name)
    cmake_parse_arguments(T "FAIL" "OUTPUT;FORBID" "ARGS" ${ARGN})
    add_test(NAME cli.${name}
             COMMAND ${CMAKE_COMMAND} "-DCMD=$<TARGET_FILE:clpath>;${T_ARGS}" -DEXPECT_FAIL=${T_FAIL}
                     "-DEXPECT_OUTPUT=${T_OUTPUT}" -DFORBID_FILE=${T_FORBID}
                     -P ${CMAKE_CURRENT_SOURCE_DIR}/cli/expect.cmake)
    set_tests_properties(cli.${name} PROPERTIES ENVIRONMENT "${CLPATH_TEST_ENV}" TIMEOUT 300)
endfunction()

clpath_cli_test(devices_lists_pocl ARGS devices OUTPUT "\\[0\\]")
clpath_cli_test(render_small ARGS render --spp 2 --width 40 --height 32 -o ${CLI_OUT}/small.pfm
                OUTPUT "summary: device=.* triangles=196 .*nonfinite=0")
clpath_cli_test(bad_device FAIL ARGS render --spp 1 --device no-such-device -o ${CLI_OUT}/bad_device.pfm
                OUTPUT "no-such-device.*no device name matches" FORBID ${CLI_OUT}/bad_device.pfm)
clpath_cli_test(bad_device_index FAIL ARGS render --spp 1 --device 99 -o ${CLI_OUT}/bad_index.pfm
                OUTPUT "99: no device with that index" FORBID ${CLI_OUT}/bad_index.pfm)
clpath_cli_test(missing_output_folder FAIL ARGS render --spp 1 -o ${CLI_OUT}/no/such/folder/x.png
                OUTPUT "folder .*no/such/folder does not exist")
clpath_cli_test(unknown_output_format FAIL ARGS render --spp 1 -o ${CLI_OUT}/x.bmp
                OUTPUT "unknown image format '.bmp'")
clpath_cli_test(unknown_scene FAIL ARGS render no-such-scene --spp 1 -o ${CLI_OUT}/x.pfm
                OUTPUT "no-such-scene")
clpath_cli_test(bad_spp FAIL ARGS render --spp 0 OUTPUT "spp")
clpath_cli_test(bad_spp_text FAIL ARGS render --spp many OUTPUT "spp")
clpath_cli_test(bad_rr FAIL ARGS render --rr sometimes OUTPUT "rr")
clpath_cli_test(no_subcommand FAIL ARGS "" OUTPUT "subcommand")
