# clpath bench rays (its Embree baseline and the kernels' work-group facts),
# clpath bench build and bench render-ab from the command line. Included from tests/CMakeLists.txt
# after cli/cli_tests.cmake (it uses clpath_cli_test, clpath_bench_quick_test,
# RAYS_HEADER and CLI_OUT from there).

# Every kernel's private memory and preferred work-group multiple, as the driver reports them.
clpath_cli_test(bench_rays_kernel_info ARGS bench rays cornell --quick --no-embree
                OUTPUT "kernel batch_trace_closest: private [0-9]+ B, local [0-9]+ B, preferred multiple [1-9][0-9]*, at most [1-9][0-9]* per group")

if(CLPATH_WITH_EMBREE)
    # Embree traces the same rays, in its default mode and robust; every ray is checked against the
    # CPU reference, like the device's. Robust mode is watertight, as the reference: no mismatch.
    clpath_bench_quick_test(rays_quick_embree ${CLI_OUT}/rays-embree.csv "${RAYS_HEADER}" embree_robust_mismatched 3
                            bench rays cornell --quick)
    clpath_bench_quick_test(rays_quick_embree_room ${CLI_OUT}/rays-embree-room.csv "${RAYS_HEADER}" embree_robust_mismatched 3
                            bench rays room:3000 --quick)
    # Each batch names both ratios, the default mode's first.
    clpath_cli_test(bench_rays_embree_ratio ARGS bench rays cornell --quick
                    OUTPUT "shadow: 12288 rays .*\n  Embree default mode: [0-9]+ hit, [0-9.]+ ms mean / [0-9.]+ ms best, [0-9.]+ Mrays/s, clpath/Embree [0-9.]+; CPU check: 12288 rays, [0-9.]+ % identical hits, [0-9]+ ties, [0-9]+ at the origin, [0-9]+ mismatched\n  Embree robust mode: [0-9]+ hit, [0-9.]+ ms mean / [0-9.]+ ms best, [0-9.]+ Mrays/s, clpath/Embree [0-9.]+; CPU check: 12288 rays, [0-9.]+ % identical hits, [0-9]+ ties, [0-9]+ at the origin, 0 mismatched")
    # bench scaling: Embree's default mode beside each BVH row (every rate non-zero: the quick batches are a few
    # thousand rays, which a loaded machine may trace at under 1 Mrays/s), none beside the flat ones.
    clpath_cli_test(bench_scaling_embree_columns ARGS bench scaling --quick
                    OUTPUT "100 bvh: [^\n]* \\(Embree ([1-9][0-9]*\\.[0-9]+|0\\.[0-9]*[1-9][0-9]*) ([1-9][0-9]*\\.[0-9]+|0\\.[0-9]*[1-9][0-9]*) ([1-9][0-9]*\\.[0-9]+|0\\.[0-9]*[1-9][0-9]*)\\)[^\n]*\n100 flat: [^\n]*\\(Embree 0\\.000 0\\.000 0\\.000\\)")
    set_tests_properties(cli.bench.rays_quick_embree cli.bench.rays_quick_embree_room cli.bench_rays_embree_ratio
                         cli.bench_scaling_embree_columns PROPERTIES LABELS cli)
endif()
# --no-embree leaves the Embree columns out (and blank in the table).
clpath_cli_test(bench_scaling_no_embree ARGS bench scaling --quick --no-embree
                OUTPUT "100 bvh: [^\n]*\\(Embree 0\\.000 0\\.000 0\\.000\\)[^\n]*\n[^|]*\n\\| triangles \\|[^\n]*\\| Embree primary \\| Embree shadow \\| Embree diffuse \\|[^\n]*\n[^\n]*\n\\| 100 \\| bvh \\|( [^|]* \\|)( [^|]* \\|)( [^|]* \\|)( [^|]* \\|)( [^|]* \\|)( [^|]* \\|)( [^|]* \\|)( [^|]* \\|)( [^|]* \\|)  \\|  \\|  \\|")

clpath_cli_test(bench_build_reports ARGS bench build room:3000 --repeat 2 --threads 2 --csv ${CLI_OUT}/build.csv
                OUTPUT "room-[0-9]+, [0-9]+ triangles, 2 threads, median [0-9.]+ ms of 2, [0-9.]+ Mtris/s, SAH [0-9.]+, [0-9]+ nodes")
clpath_cli_test(bench_build_unknown_scene FAIL ARGS bench build no-such-scene
                OUTPUT "no built-in scene named 'no-such-scene' \\(built-in: ")
clpath_cli_test(bench_build_bad_bins FAIL ARGS bench build cornell --bins 1 OUTPUT "--bins: Value 1 not in range 2 to 256")

# --save-rays: the three batches' files, checked field by field against what the run printed.
add_test(NAME cli.bench.rays_save_rays
         COMMAND ${CMAKE_COMMAND} "-DCMD=$<TARGET_FILE:clpath>;bench;rays;cornell;--quick;--no-embree"
                 -DDIR=${CLI_OUT}/saved-rays -P ${CMAKE_CURRENT_SOURCE_DIR}/bench/save_rays.cmake)
set_tests_properties(cli.bench.rays_save_rays PROPERTIES ENVIRONMENT "${CLPATH_TEST_ENV}" TIMEOUT 300)
clpath_cli_test(bench_rays_save_rays_missing_folder FAIL ARGS bench rays cornell --quick --no-embree
                --save-rays ${CLI_OUT}/no-such-rays-folder OUTPUT "--save-rays .*/no-such-rays-folder: folder does not exist")
clpath_cli_test(bench_rays_save_rays_not_a_folder FAIL ARGS bench rays cornell --quick --no-embree
                --save-rays ${CMAKE_SOURCE_DIR}/scenes/bunny.json OUTPUT "--save-rays .*bunny.json: is a file, not a folder")

# --ab-kernels: a variant timed against the built-in kernels (an unchanged copy: its answers are the same).
# Read by two tests, written by none: kept apart from the outputs.
set(AB_KERNELS ${CMAKE_BINARY_DIR}/test-inputs/ab-kernels)
file(MAKE_DIRECTORY ${AB_KERNELS})
configure_file(${CMAKE_SOURCE_DIR}/kernels/traverse.cl ${AB_KERNELS}/traverse.cl COPYONLY)
clpath_cli_test(bench_rays_ab_kernels ARGS bench rays cornell --quick --no-embree --ab-kernels ${AB_KERNELS}
                OUTPUT "diffuse: [0-9]+ rays .*\n  A/B: variant/built-in [0-9.]+ \\(quartiles [0-9.]+-[0-9.]+\\) over 1 launch pairs; answers differ for 0 rays")
clpath_cli_test(bench_rays_ab_kernels_missing_folder FAIL ARGS bench rays cornell --quick --no-embree
                --ab-kernels ${CLI_OUT}/no-such-kernels-folder OUTPUT "--ab-kernels .*/no-such-kernels-folder: no such folder")
clpath_cli_test(bench_rays_ab_kernels_no_kernel_files FAIL ARGS bench rays cornell --quick --no-embree
                --ab-kernels ${CMAKE_SOURCE_DIR}/tests/cli/data OUTPUT "--ab-kernels .*data: no kernel files")
clpath_cli_test(bench_rays_ab_options ARGS bench rays cornell --quick --no-embree --ab-options=-DCLP_UNREAD_DEFINE
                OUTPUT "primary: [0-9]+ rays .*\n  A/B: variant/built-in [0-9.]+ \\(quartiles [0-9.]+-[0-9.]+\\) over 1 launch pairs; answers differ for 0 rays")

# bench render-ab: the renderer's kernels against a variant (an unchanged copy: the same image).
clpath_cli_test(bench_render_ab ARGS bench render-ab cornell --quick --ab-kernels ${AB_KERNELS}
                OUTPUT "A/B: variant/built-in [0-9.]+ \\(quartiles [0-9.]+-[0-9.]+\\) over 2 launch pairs; built-in [0-9.]+ Msamples/s, variant [0-9.]+; images differ in 0 of 768 pixels")
# The two kernel shapes side by side: the same image (a ';' would split the pattern: '.' stands for it).
clpath_cli_test(bench_render_ab_shapes ARGS bench render-ab cornell --quick --ab-shape wavefront
                OUTPUT "over 2 launch pairs. built-in \\(mega\\) [0-9.]+ Msamples/s, variant \\(wavefront\\) [0-9.]+. images differ in 0 of 768 pixels")
clpath_cli_test(bench_render_ab_no_variant FAIL ARGS bench render-ab cornell --spp 1
                OUTPUT "bench render-ab: give the variant: --ab-kernels DIR, --ab-options OPTS, --ab-shape SHAPE or several")
clpath_cli_test(bench_render_ab_missing_folder FAIL ARGS bench render-ab cornell --spp 1 --ab-kernels ${CLI_OUT}/no-such-kernels
                OUTPUT "--ab-kernels .*no-such-kernels: no such folder")
