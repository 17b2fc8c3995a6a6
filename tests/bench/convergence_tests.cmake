# clpath bench convergence and clpath export from the command line: the quick
# mode runs in seconds against the committed Cycles reference, and bad input
# fails cleanly. Included from tests/CMakeLists.txt after cli/cli_tests.cmake
# (it uses clpath_cli_test and CLI_OUT from there).
set(CONVERGENCE_REF ${CMAKE_SOURCE_DIR}/benchmarks/references/cornell-classic-cycles.exr)
set(CLASSIC ${CMAKE_SOURCE_DIR}/scenes/cornell-classic.json)

if(CLPATH_WITH_OIIO)  # the reference is an EXR
    add_test(NAME bench.convergence_quick
             COMMAND ${CMAKE_COMMAND}
                     "-DCMD=$<TARGET_FILE:clpath>;bench;convergence;${CLASSIC};--reference;${CONVERGENCE_REF};--quick;--mask-above;0.8;--mask-grow;1;--csv;${CLI_OUT}/convergence.csv;--md;${CLI_OUT}/convergence.md"
                     -DCSV=${CLI_OUT}/convergence.csv -DMD=${CLI_OUT}/convergence.md
                     "-DCONFIGS=thesis;cosine;no-rr;throughput-rr;nee-mis;clpath"
                     -P ${CMAKE_CURRENT_SOURCE_DIR}/bench/check_convergence.cmake)
    set_tests_properties(bench.convergence_quick PROPERTIES ENVIRONMENT "${CLPATH_TEST_ENV}" TIMEOUT 300)

    clpath_cli_test(bench.convergence_bad_size FAIL
                    ARGS bench convergence ${CLASSIC} --reference ${CONVERGENCE_REF} --width 33 --max-spp 1
                    OUTPUT "cornell-classic-cycles.exr: reference is 128x128, which is not the render size 33x33 or an integer multiple of it")
    clpath_cli_test(bench.convergence_missing_csv_folder FAIL
                    ARGS bench convergence ${CLASSIC} --reference ${CONVERGENCE_REF} --quick
                         --csv ${CLI_OUT}/no/such/folder/c.csv
                    OUTPUT "output .*/no/such/folder/c\\.csv: folder .*/no/such/folder does not exist")
    clpath_cli_test(bench.convergence_unknown_scene FAIL
                    ARGS bench convergence no-such-scene --reference ${CONVERGENCE_REF} --quick
                         --csv ${CLI_OUT}/unknown-scene.csv
                    OUTPUT "no built-in scene named 'no-such-scene' \\(built-in: " FORBID ${CLI_OUT}/unknown-scene.csv)
endif()
clpath_cli_test(bench.convergence_no_reference FAIL ARGS bench convergence ${CLASSIC} --quick
                OUTPUT "--reference is required")
clpath_cli_test(bench.convergence_missing_reference FAIL
                ARGS bench convergence ${CLASSIC} --reference ${CLI_OUT}/no-such-reference.exr
                OUTPUT "--reference: File does not exist: .*/no-such-reference\\.exr")
clpath_cli_test(bench.convergence_unknown_config FAIL
                ARGS bench convergence ${CLASSIC} --reference ${CLASSIC} --configs thesis,magic
                OUTPUT "--configs: magic not in \\{thesis,cosine,no-rr,throughput-rr,nee-mis,bvh,clpath,lights-power,lights-bvh\\}")
clpath_cli_test(bench.convergence_zero_spp FAIL
                ARGS bench convergence ${CLASSIC} --reference ${CLASSIC} --max-spp 0
                OUTPUT "--max-spp: '0' is not a whole number from 1 to 2147483648")
clpath_cli_test(bench.convergence_reference_not_an_image FAIL
                ARGS bench convergence ${CLASSIC} --reference ${CLASSIC} --quick
                OUTPUT "cannot read .*/scenes/cornell-classic\\.json: ")

# clpath export: writes the three files; refuses glass; names its output rule.
clpath_cli_test(export.cornell_classic ARGS export ${CLASSIC} ${CLI_OUT}/export-classic.json --width 32 --height 32
                OUTPUT "wrote .*export-classic.json, .*export-classic.obj, .*export-classic.mtl: 32 triangles, 32x32")
clpath_cli_test(export.refuses_glass FAIL
                ARGS export ${CMAKE_SOURCE_DIR}/scenes/cornell-thesis.json ${CLI_OUT}/export-glass.json
                OUTPUT "cannot export: material 'glass' is a dielectric" FORBID ${CLI_OUT}/export-glass.obj)
clpath_cli_test(export.needs_json_name FAIL ARGS export ${CLASSIC} ${CLI_OUT}/export.obj
                OUTPUT "output .*/export\\.obj: must end in \\.json \\(the OBJ and MTL go beside it\\)" FORBID ${CLI_OUT}/export.obj)
