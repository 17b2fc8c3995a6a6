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

clpath_cli_test(devices_lists_pocl ARGS devices
                OUTPUT "Portable Computing Language\n  \\[0\\] [^\n]+ \\(CPU, Portable Computing Language, OpenCL ")
clpath_cli_test(render_small ARGS render --spp 2 --width 40 --height 32 -o ${CLI_OUT}/small.pfm
                OUTPUT "summary: device=.* triangles=196 .*nonfinite=0")
clpath_cli_test(bad_device FAIL ARGS render --spp 1 --device no-such-device -o ${CLI_OUT}/bad_device.pfm
                OUTPUT "--device 'no-such-device': no device name matches\\. Devices:\n  \\[0\\] " FORBID ${CLI_OUT}/bad_device.pfm)
clpath_cli_test(bad_device_index FAIL ARGS render --spp 1 --device 99 -o ${CLI_OUT}/bad_index.pfm
                OUTPUT "--device 99: no device with that index \\(the indices are 0 to [0-9]+\\)" FORBID ${CLI_OUT}/bad_index.pfm)
clpath_cli_test(missing_output_folder FAIL ARGS render --spp 1 -o ${CLI_OUT}/no/such/folder/x.png
                OUTPUT "output .*/no/such/folder/x\\.png: folder .*/no/such/folder does not exist")
clpath_cli_test(unknown_output_format FAIL ARGS render --spp 1 -o ${CLI_OUT}/x.bmp
                OUTPUT "output .*/x\\.bmp: unknown image format '\\.bmp' \\(use \\.png, \\.exr or \\.pfm\\)"
                FORBID ${CLI_OUT}/x.bmp)
clpath_cli_test(unknown_scene FAIL ARGS render no-such-scene --spp 1 -o ${CLI_OUT}/unknown-scene.pfm
                OUTPUT "no built-in scene named 'no-such-scene' \\(built-in: cornell scaling:N room:N bunnies:N city:N\\)"
                FORBID ${CLI_OUT}/unknown-scene.pfm)
clpath_cli_test(bad_spp_text FAIL ARGS render --spp many OUTPUT "--spp: 'many' is not a whole number from 1 to 4294967295")
# Beyond the 32-bit sample index the kernels use (host/render/renderer.hpp kMaxSamplesPerPixel).
clpath_cli_test(spp_beyond_sample_index FAIL ARGS render --spp 4294967296 OUTPUT "--spp: '4294967296' is not a whole number from 1 to 4294967295")
clpath_cli_test(bad_rr FAIL ARGS render --rr sometimes OUTPUT "--rr: sometimes not in \\{none,throughput,depth\\}")

# --- scenes: bundled scenes render, bad scene input fails cleanly ---------------------
# Like clpath_cli_test, with extra environment variables (ENV "A=1;B=2").
set(SCENE_DATA ${CMAKE_CURRENT_SOURCE_DIR}/scene/data)
function(clpath_scene_cli_test name)
    cmake_parse_arguments(T "FAIL" "OUTPUT;FORBID" "ARGS;ENV" ${ARGN})
    add_test(NAME cli.scene.${name}
             COMMAND ${CMAKE_COMMAND} "-DCMD=$<TARGET_FILE:clpath>;${T_ARGS}" -DEXPECT_FAIL=${T_FAIL}
                     "-DEXPECT_OUTPUT=${T_OUTPUT}" -DFORBID_FILE=${T_FORBID}
                     -P ${CMAKE_CURRENT_SOURCE_DIR}/cli/expect.cmake)
    set_tests_properties(cli.scene.${name} PROPERTIES ENVIRONMENT "${CLPATH_TEST_ENV};${T_ENV}" TIMEOUT 300)
endfunction()

foreach(scene cornell-thesis cornell-thesis-diffuse cornell-classic bunny)
    clpath_scene_cli_test(render_${scene} ARGS render ${CMAKE_SOURCE_DIR}/scenes/${scene}.json --spp 1 --width 40
                          --height 32 -o ${CLI_OUT}/${scene}.pfm
                          OUTPUT "summary: .*nonfinite=0.*loaded '${scene}' from .* in [0-9.]+ s.*BVH: .* built in ")
endforeach()
clpath_scene_cli_test(render_scaling ARGS render scaling:10000 --spp 1 --width 40 --height 32 -o ${CLI_OUT}/scaling.pfm
                      OUTPUT "triangles=10008 .*loaded 'scaling-10008' from scaling:10000")
clpath_scene_cli_test(render_bare_obj ARGS render /usr/share/glmark2/models/bunny.obj --spp 1 --width 40 --height 32
                      -o ${CLI_OUT}/bare-bunny.pfm OUTPUT "triangles=69668 ")  # with the ground's two

clpath_scene_cli_test(file_not_found FAIL ARGS render ${SCENE_DATA}/no-such-scene.json -o ${CLI_OUT}/nf.pfm
                      OUTPUT "no-such-scene.json: no such file" FORBID ${CLI_OUT}/nf.pfm)
clpath_scene_cli_test(folder_not_file FAIL ARGS render ${SCENE_DATA} -o ${CLI_OUT}/folder.pfm
                      OUTPUT "data: is a folder, not a scene file" FORBID ${CLI_OUT}/folder.pfm)
clpath_scene_cli_test(unknown_file_type FAIL ARGS render ${SCENE_DATA}/unknown-type.txt -o ${CLI_OUT}/type.pfm
                      OUTPUT "unknown-type.txt: unknown scene file type '.txt'" FORBID ${CLI_OUT}/type.pfm)
clpath_scene_cli_test(malformed_json FAIL ARGS render ${SCENE_DATA}/malformed.json -o ${CLI_OUT}/malformed.pfm
                      OUTPUT "malformed.json:4:31: syntax error" FORBID ${CLI_OUT}/malformed.pfm)
clpath_scene_cli_test(unknown_field FAIL ARGS render ${SCENE_DATA}/unknown-field.json -o ${CLI_OUT}/unknown.pfm
                      OUTPUT "unknown-field.json: objects\\[1\\]\\.transform\\.scle: unknown field"
                      FORBID ${CLI_OUT}/unknown.pfm)
clpath_scene_cli_test(out_of_range FAIL ARGS render ${SCENE_DATA}/out-of-range.json -o ${CLI_OUT}/range.pfm
                      OUTPUT "out-of-range.json: materials\\.white\\.albedo\\[1\\]: 1\\.5 is out of range \\(must be \\[0, 1\\]\\)"
                      FORBID ${CLI_OUT}/range.pfm)
clpath_scene_cli_test(wrong_type FAIL ARGS render ${SCENE_DATA}/wrong-type.json -o ${CLI_OUT}/wrong-type.pfm
                      OUTPUT "wrong-type.json: camera\\.vfov: expected a number, got string" FORBID ${CLI_OUT}/wrong-type.pfm)
clpath_scene_cli_test(missing_material FAIL ARGS render ${SCENE_DATA}/missing-material.json -o ${CLI_OUT}/mat.pfm
                      OUTPUT "missing-material.json: objects\\[1\\]\\.material: no material named 'chrome'"
                      FORBID ${CLI_OUT}/mat.pfm)
clpath_scene_cli_test(missing_mesh FAIL ARGS render ${SCENE_DATA}/missing-mesh.json -o ${CLI_OUT}/mesh.pfm
                      OUTPUT "missing-mesh.json: objects\\[0\\]\\.file: .*meshes/nowhere.obj: no such file"
                      FORBID ${CLI_OUT}/mesh.pfm)
clpath_scene_cli_test(obj_index_out_of_range FAIL ARGS render ${SCENE_DATA}/bad-mesh.json -o ${CLI_OUT}/index.pfm
                      OUTPUT "bad-index.obj:6: face: vertex index 7 is out of range" FORBID ${CLI_OUT}/index.pfm)
clpath_scene_cli_test(obj_nan FAIL ARGS render ${SCENE_DATA}/nan.obj -o ${CLI_OUT}/nan.pfm
                      OUTPUT "nan.obj:3: vertex: 'nan' is not a finite number" FORBID ${CLI_OUT}/nan.pfm)
clpath_scene_cli_test(obj_short_face FAIL ARGS render ${SCENE_DATA}/short-face.obj -o ${CLI_OUT}/short.pfm
                      OUTPUT "short-face.obj:6: face has 2 corners, at least 3 are needed" FORBID ${CLI_OUT}/short.pfm)
clpath_scene_cli_test(obj_no_faces FAIL ARGS render ${SCENE_DATA}/no-faces.obj -o ${CLI_OUT}/nofaces.pfm
                      OUTPUT "no-faces.obj: the mesh has no faces \\(an empty scene\\)" FORBID ${CLI_OUT}/nofaces.pfm)
clpath_scene_cli_test(empty_scene FAIL ARGS render ${SCENE_DATA}/empty.json -o ${CLI_OUT}/empty.pfm
                      OUTPUT "empty.json: objects: the scene is empty" FORBID ${CLI_OUT}/empty.pfm)
clpath_scene_cli_test(degenerate_dropped ARGS render ${SCENE_DATA}/degenerate.obj --spp 1 -o ${CLI_OUT}/degenerate.pfm
                      OUTPUT "summary: .*triangles=4 .*warning: dropped 2 degenerate triangles")  # and the ground's two
clpath_scene_cli_test(no_emitter_renders_black ARGS render ${SCENE_DATA}/no-emitter.json --spp 1 -o ${CLI_OUT}/dark.pfm
                      OUTPUT "warning: scene 'no-emitter' has no emitter; the image will be black.*wrote .*dark.pfm")
clpath_scene_cli_test(too_large_for_device FAIL ENV CLPATH_DEVICE_MEMORY_LIMIT=4096
                      ARGS render ${CMAKE_SOURCE_DIR}/scenes/cornell-classic.json --spp 1 -o ${CLI_OUT}/large.pfm
                      OUTPUT "cornell-classic.json: .* needs .*more than .*CLPATH_DEVICE_MEMORY_LIMIT"
                      FORBID ${CLI_OUT}/large.pfm)
clpath_scene_cli_test(unwritable_output FAIL ARGS render ${CMAKE_SOURCE_DIR}/scenes/cornell-classic.json --spp 1
                      -o ${CLI_OUT}/missing-folder/x.png
                      OUTPUT "output .*/missing-folder/x\\.png: folder .*/missing-folder does not exist")

# --- benchmarks: quick modes (seconds each) and bad arguments ---------------------------
function(clpath_bench_quick_test name csv header zero_column min_rows)
    add_test(NAME cli.bench.${name}
             COMMAND ${CMAKE_COMMAND} "-DCMD=$<TARGET_FILE:clpath>;${ARGN};--csv;${csv}" -DCSV=${csv}
                     "-DHEADER=${header}" -DMIN_ROWS=${min_rows} -DZERO_COLUMN=${zero_column}
                     -P ${CMAKE_CURRENT_SOURCE_DIR}/bench/bench_quick.cmake)
    set_tests_properties(cli.bench.${name} PROPERTIES ENVIRONMENT "${CLPATH_TEST_ENV}" TIMEOUT 300)
endfunction()
set(RAYS_HEADER "^device,scene,triangles,accel,batch,width,height,workgroup,rays,hits,launches,mean_ms,best_ms,mrays_per_s,checked,identical_percent,ties,near_origin,mismatched,max_dt,embree_default_mean_ms,embree_default_mrays_per_s,clpath_over_embree_default,embree_default_mismatched,embree_robust_mean_ms,embree_robust_mrays_per_s,clpath_over_embree_robust,embree_robust_mismatched$")
set(SCALING_HEADER "^device,requested,triangles,accel,generate_ms,build_ms,build_mtris_per_s,sah_cost,nodes,bytes_per_triangle,primary_mrays_per_s,shadow_mrays_per_s,diffuse_mrays_per_s,path_msamples_per_s,path_mrays_per_s,checked_rays,mismatched,seconds,embree_primary_mrays_per_s,embree_shadow_mrays_per_s,embree_diffuse_mrays_per_s,embree_mismatched,skipped$")
# Every ray of the quick batches is checked on the CPU: no mismatch is allowed.
clpath_bench_quick_test(rays_quick_bvh ${CLI_OUT}/rays-bvh.csv "${RAYS_HEADER}" mismatched 3 bench rays cornell --quick)
clpath_bench_quick_test(rays_quick_flat ${CLI_OUT}/rays-flat.csv "${RAYS_HEADER}" mismatched 3
                        bench rays cornell --quick --accel flat)
clpath_bench_quick_test(rays_quick_room ${CLI_OUT}/rays-room.csv "${RAYS_HEADER}" mismatched 3
                        bench rays room:3000 --quick --workgroup 32)
clpath_bench_quick_test(scaling_quick ${CLI_OUT}/scaling.csv "${SCALING_HEADER}" mismatched 6 bench scaling --quick)
clpath_cli_test(bench_rays_prints_agreement ARGS bench rays cornell --quick
                OUTPUT "primary: 12288 rays .*100.0000 % identical hits, [0-9]+ ties, [0-9]+ at the origin, 0 mismatched")
clpath_cli_test(bench_rays_width_not_tiled FAIL ARGS bench rays cornell --width 30 --height 32
                OUTPUT "width and height must be positive multiples of 4 \\(rays come in 4x4-pixel tiles\\), got 30x32")
clpath_cli_test(bench_rays_bad_light FAIL ARGS bench rays cornell --quick --light 1,2 OUTPUT "--light '1,2': expected x,y,z")
clpath_cli_test(bench_rays_bad_camera FAIL ARGS bench rays cornell --quick --camera 0,0,0,1,1,x
                OUTPUT "--camera '0,0,0,1,1,x': 'x' is not a finite number")
clpath_cli_test(bench_rays_unknown_scene FAIL ARGS bench rays no-such-scene --quick
                OUTPUT "no built-in scene named 'no-such-scene' \\(built-in: ")
clpath_cli_test(bench_rays_bad_accel FAIL ARGS bench rays cornell --quick --accel kd OUTPUT "--accel: kd not in \\{bvh,flat\\}")
clpath_cli_test(bench_rays_missing_csv_folder FAIL ARGS bench rays cornell --quick --csv ${CLI_OUT}/no/such/x.csv
                OUTPUT "--csv .*/no/such/x\\.csv: folder .*/no/such does not exist" FORBID ${CLI_OUT}/no/such/x.csv)
clpath_cli_test(bench_rays_huge_workgroup FAIL ARGS bench rays cornell --quick --workgroup 65536
                OUTPUT "work-group size 65536 exceeds [^\n]+'s limit of [0-9]+")
clpath_cli_test(bench_scaling_min_too_small FAIL ARGS bench scaling --min 10 OUTPUT "--min 10: expected a whole number of triangles from 100 to 50000000")
clpath_cli_test(bench_scaling_min_over_max FAIL ARGS bench scaling --min 1000 --max 100
                OUTPUT "--min 1000 is larger than --max 100")
clpath_cli_test(bench_scaling_bad_accel FAIL ARGS bench scaling --accel kd OUTPUT "--accel: kd not in \\{both,bvh,flat\\}")
clpath_cli_test(render_flat_accel ARGS render --spp 1 --width 40 --height 32 --accel flat -o ${CLI_OUT}/flat.pfm
                OUTPUT "summary: .*triangles=196 .*nonfinite=0 accel=flat")
clpath_cli_test(render_bad_accel FAIL ARGS render --spp 1 --accel kd OUTPUT "--accel: kd not in \\{bvh,flat\\}")
clpath_scene_cli_test(render_closed_room ARGS render room:2000 --spp 1 --width 40 --height 32 -o ${CLI_OUT}/room.pfm
                      OUTPUT "triangles=1994 .*loaded 'room-1994' from room:2000")

# --- export --format mitsuba: a Mitsuba 3 scene dictionary and one mesh per material ---
clpath_cli_test(export.mitsuba ARGS export ${CMAKE_SOURCE_DIR}/scenes/cornell-thesis.json
                ${CLI_OUT}/thesis-mitsuba.json --format mitsuba --width 32 --height 26
                OUTPUT "wrote .*thesis-mitsuba.json and 7 meshes: Mitsuba 3, 196 triangles, 32x26, max depth 16")
clpath_cli_test(export.unknown_format FAIL ARGS export ${CMAKE_SOURCE_DIR}/scenes/cornell-thesis.json
                ${CLI_OUT}/thesis-pbrt.json --format pbrt OUTPUT "--format: pbrt not in \\{obj,mitsuba,embree\\}"
                FORBID ${CLI_OUT}/thesis-pbrt.json)

# glTF: a model renders from the command line; a broken one names its glTF path and writes nothing.
clpath_scene_cli_test(render_gltf ARGS render ${CMAKE_SOURCE_DIR}/scenes/suzanne/Suzanne.gltf --spp 1 --width 40
                      --height 30 -o ${CLI_OUT}/suzanne.pfm OUTPUT "summary: device=.* triangles=3938 ")  # with the ground's two
clpath_scene_cli_test(gltf_bad_index FAIL ARGS render ${SCENE_DATA}/bad-index.gltf -o ${CLI_OUT}/bad-gltf.pfm
                      OUTPUT "bad-index.gltf: meshes\\[0\\]\\.primitives\\[0\\]\\.indices: index 9 at position 5 is out of range"
                      FORBID ${CLI_OUT}/bad-gltf.pfm)
include(${CMAKE_CURRENT_SOURCE_DIR}/cli/usage_tests.cmake)
include(${CMAKE_CURRENT_SOURCE_DIR}/cli/hostile_files_tests.cmake)

# The progress printer's line schedule (host/cli is the program, not the
# library: its source is built into the test).
target_sources(progress_test PRIVATE ${CMAKE_SOURCE_DIR}/host/cli/progress.cpp)
# A render logging to a file writes a line at least every interval (shortened
# to 1 s here by CLPATH_PROGRESS_INTERVAL_MS).
add_test(NAME cli.progress_lines_in_a_log
         COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/cli/progress_log.sh $<TARGET_FILE:clpath> ${CLI_OUT}/progress)
set_tests_properties(cli.progress_lines_in_a_log PROPERTIES ENVIRONMENT "${CLPATH_TEST_ENV}" TIMEOUT 300)

# Adaptive sampling: a scene whose every pixel is exactly 1 (a mirror box in a
# white environment) meets any noise target at the first decision past the
# minimum (max(16, 4/sqrt(R)) samples, decisions every 32); the scene file's
# render block gives the target and the command line overrides it.
clpath_cli_test(adaptive_scene_file_target ARGS render ${CMAKE_CURRENT_SOURCE_DIR}/cli/data/adaptive-easy.json
                -o ${CLI_OUT}/adaptive-easy.pfm --sample-count-image ${CLI_OUT}/adaptive-easy-n.pfm
                OUTPUT "summary: .*spp=64 .*noise_target=0.01 spp_min=64 spp_max=64 spp_mean=64.00 converged=1")
clpath_cli_test(adaptive_option_overrides_scene ARGS render ${CMAKE_CURRENT_SOURCE_DIR}/cli/data/adaptive-easy.json
                --noise-target 0.2 -o ${CLI_OUT}/adaptive-easy-02.pfm
                OUTPUT "noise_target=0.2 spp_min=32 spp_max=32 spp_mean=32.00 converged=1")
clpath_cli_test(adaptive_target_zero FAIL ARGS render --noise-target 0 -o ${CLI_OUT}/adaptive-zero.pfm
                OUTPUT "--noise-target: '0' is not a finite number above 0 and up to 1" FORBID ${CLI_OUT}/adaptive-zero.pfm)
clpath_cli_test(adaptive_odd_chunk FAIL ARGS render --noise-target 0.1 --chunk 3 -o ${CLI_OUT}/adaptive-odd.pfm
                OUTPUT "--noise-target: adaptive sampling needs chunks of an even number of samples \\(--chunk 3 is odd\\)"
                FORBID ${CLI_OUT}/adaptive-odd.pfm)

# --- light samplers: a scene file's choice, Auto's, and the command line's over both
clpath_cli_test(render_light_sampler_from_scene ARGS render ${CMAKE_SOURCE_DIR}/scenes/room-lamp-sky.json --spp 1
                --width 16 --height 12 -o ${CLI_OUT}/room-lamp-sky.pfm
                OUTPUT "summary: .* light_sampler=bvh light_bvh_nodes=3 light_bvh_depth=1 ")
clpath_cli_test(render_light_sampler_auto_city ARGS render city:100 --spp 1 --width 16 --height 12 -o ${CLI_OUT}/city.pfm
                OUTPUT "summary: .* light_sampler=bvh light_bvh_nodes=399 ")
clpath_cli_test(render_light_sampler_forced_power ARGS render city:100 --light-sampler power --spp 1 --width 16 --height 12
                -o ${CLI_OUT}/city-power.pfm OUTPUT "summary: .* light_sampler=power")

# --- instancing: 10,000 bunnies (7 10^8 triangles placed) render in under 10 MB of scene buffers
clpath_cli_test(render_bunnies_10000 ARGS render bunnies:10000 --spp 1 --width 32 --height 18
                -o ${CLI_OUT}/bunnies.pfm
                OUTPUT "summary: .*triangles=696660002 .*nonfinite=0 .*scene_device_bytes=[1-9][0-9][0-9][0-9][0-9][0-9][0-9] light_sampler=power instances=10001 instanced_meshes=2 placed_triangles=696660002 tlas_bytes=")
# a textured glTF mesh placed by three nodes is stored once (the ground, flat, is the other mesh)
clpath_cli_test(render_gltf_textured_instances ARGS render ${CMAKE_SOURCE_DIR}/scenes/suzanne/suzanne-instances.gltf
                --spp 1 --width 32 --height 24 -o ${CLI_OUT}/suzanne-instances.pfm
                OUTPUT "summary: .*nonfinite=0 .* instances=4 instanced_meshes=2 placed_triangles=11810 ")
# bench instances: the two-level walk's answers are the one-level walk's over
# the flattened scene, and robust Embree's over the instances, on every ray
# (both watertight), but for hits within kNearOrigin of a ray's origin,
# counted apart as bench rays counts them; Embree's default mode is timed,
# not judged.
set(INSTANCE_BATCH "[^\n]*\n  clpath flattened: [^\n]*, 0 rays differ, [0-9]+ at the origin\n  Embree instanced default: [^\n]*\n  Embree instanced robust: [^\n]*, 0 rays differ, [0-9]+ at the origin\n  Embree flattened default: [^\n]*\n  Embree flattened robust: [^\n]*\n")
clpath_cli_test(bench_instances_agree ARGS bench instances bunnies:20 --quick
                OUTPUT "two-level: [0-9]+ bytes [^\n]*\nflattened: [0-9]+ bytes \\([0-9.]+x the two-level\\)[^\n]*\n.*primary: 12288 rays ${INSTANCE_BATCH}shadow: ${INSTANCE_BATCH}diffuse: ${INSTANCE_BATCH}")
clpath_cli_test(bench_instances_none FAIL ARGS bench instances cornell --quick
                OUTPUT "cornell: bench instances: scene 'cornell' places no mesh by instances")
clpath_cli_test(bench_instances_not_tiled FAIL ARGS bench instances bunnies:2 --width 30 --height 32
                OUTPUT "width and height must be positive multiples of 4, got 30x32")
clpath_cli_test(singular_instance FAIL ARGS render ${CMAKE_CURRENT_SOURCE_DIR}/cli/data/singular-instance.json --spp 1
                -o ${CLI_OUT}/singular-instance.pfm
                OUTPUT "singular-instance\\.json: objects\\[1\\]\\.instances\\[1\\]\\.scale: the transform is singular"
                FORBID ${CLI_OUT}/singular-instance.pfm)
