# clpath bench path from the command line. Included from tests/CMakeLists.txt
# after cli/cli_tests.cmake (it uses clpath_cli_test and CLI_OUT from there).
set(POINT_CORNELL ${CMAKE_SOURCE_DIR}/scenes/cornell-point.json)

if(CLPATH_WITH_EMBREE)
    # clpath and the Embree tracer in both modes at 32x32, their speeds (the default mode's ratio
    # first) and the agreement of the images.
    clpath_cli_test(bench.path_quick ARGS bench path ${POINT_CORNELL} --quick --csv ${CLI_OUT}/path.csv
                    OUTPUT "clpath/Embree default mode: [0-9.]+ \\(Msamples/s\\), [0-9.]+ \\(Mrays/s\\).*\nclpath/Embree robust mode: [0-9.]+ \\(Msamples/s\\), [0-9.]+ \\(Mrays/s\\).*\nagreement with Embree default mode .*: agree\nagreement with Embree robust mode .*: agree\n")
    set_tests_properties(cli.bench.path_quick PROPERTIES LABELS cli)
else()
    clpath_cli_test(bench.path_without_embree FAIL ARGS bench path ${POINT_CORNELL} --quick
                    OUTPUT "clpath: error: bench path needs Embree, and this clpath was built without it")
endif()

# A scene the Embree tracer cannot render as clpath does: exit 2 and the
# reason, before any device is opened.
add_test(NAME cli.bench.path_unsupported_scene
         COMMAND ${CMAKE_COMMAND} "-DCMD=$<TARGET_FILE:clpath>;bench;path;${CMAKE_SOURCE_DIR}/scenes/cornell-thesis.json;--quick"
                 -DEXPECT_FAIL=1 -DEXPECT_RC=2
                 "-DEXPECT_OUTPUT=clpath: error: .*cornell-thesis.json: bench path supports diffuse surfaces .*material 'glass' is a dielectric"
                 -P ${CMAKE_CURRENT_SOURCE_DIR}/cli/expect.cmake)
set_tests_properties(cli.bench.path_unsupported_scene PROPERTIES ENVIRONMENT "${CLPATH_TEST_ENV}" TIMEOUT 300)

# clpath export --format embree writes the scene for Embree's example path tracer, which (where
# embree-tools is installed) renders it; a scene it would render differently is refused.
find_program(EMBREE_PATHTRACER pathtracer)
add_test(NAME cli.export.embree_pathtracer
         COMMAND ${CMAKE_COMMAND} -DCLPATH=$<TARGET_FILE:clpath> -DSCENE=${POINT_CORNELL} -DOUT=${CLI_OUT}/embree-export
                 "-DPATHTRACER=${EMBREE_PATHTRACER}" -P ${CMAKE_CURRENT_SOURCE_DIR}/bench/embree_export.cmake)
clpath_cli_test(export.embree_emitter FAIL ARGS export ${CMAKE_SOURCE_DIR}/scenes/cornell-classic.json
                ${CLI_OUT}/embree-emitter/x.ecs --format embree
                OUTPUT "cornell-classic.json: cannot export: material 'light' emits light" FORBID ${CLI_OUT}/embree-emitter/x.ecs)
clpath_cli_test(export.embree_not_ecs FAIL ARGS export ${POINT_CORNELL} ${CLI_OUT}/embree-json.json --format embree
                OUTPUT "--format embree writes an Embree command script, NAME.ecs" FORBID ${CLI_OUT}/embree-json.json)
set_tests_properties(cli.export.embree_pathtracer cli.export.embree_emitter cli.export.embree_not_ecs
                     PROPERTIES LABELS cli ENVIRONMENT "${CLPATH_TEST_ENV}" TIMEOUT 300)
