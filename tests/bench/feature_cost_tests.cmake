# benchmarks/feature_cost/run.sh in its quick mode (one round, tiny images,
# room:3000 written as .glb and single-file .gltf by obj_to_glb.py), so that
# the script, its scene variants and the glTF writer do not rot; the numbers
# it prints mean nothing. Included from tests/CMakeLists.txt after
# cli/cli_tests.cmake (it uses CLI_OUT and expect.cmake from there).
file(REMOVE_RECURSE ${CLI_OUT}/feature-cost ${CLI_OUT}/feature-cost-work)
add_test(NAME bench.feature_cost_quick
         COMMAND ${CMAKE_COMMAND}
                 "-DCMD=env;QUICK=1;CLPATH=$<TARGET_FILE:clpath>;OUT_DIR=${CLI_OUT}/feature-cost;WORK=${CLI_OUT}/feature-cost-work;bash;${CMAKE_SOURCE_DIR}/benchmarks/feature_cost/run.sh;all"
                 "-DEXPECT_OUTPUT=\\| bunny \\| --all-features \\| [0-9.]+ .*\\| suzanne-textured \\| this \\| [0-9.]+ .*room.glb: 2984 triangles.*\\| room.gltf \\| - \\| [0-9.]+ "
                 -P ${CMAKE_CURRENT_SOURCE_DIR}/cli/expect.cmake)
set_tests_properties(bench.feature_cost_quick PROPERTIES ENVIRONMENT "${CLPATH_TEST_ENV}" TIMEOUT 300)
