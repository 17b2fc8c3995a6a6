# The command line as a finished tool: every error starts "clpath: error:",
# names the option and what it accepts, and exits 2 for bad usage, 1 for a
# run that failed. Each test checks the exact exit status.
set(CLI_DATA ${CMAKE_CURRENT_SOURCE_DIR}/cli/data)
set(USAGE_OUT ${CMAKE_BINARY_DIR}/cli-usage-out)
file(MAKE_DIRECTORY ${USAGE_OUT})
# Read by two tests, written by none: kept apart from the outputs.
set(A_FOLDER ${CMAKE_BINARY_DIR}/test-inputs/a-folder)
file(MAKE_DIRECTORY ${A_FOLDER})

# clpath_usage_test(name RC n [OUTPUT regex] [REJECT regex] [FORBID path] [MAKES path] [ENV "A=1;B=2"] ARGS ...)
function(clpath_usage_test name)
    cmake_parse_arguments(T "" "RC;OUTPUT;REJECT;FORBID;MAKES" "ARGS;ENV" ${ARGN})
    set(fail 0)
    if(NOT T_RC EQUAL 0)
        set(fail 1)
    endif()
    add_test(NAME cli.usage.${name}
             COMMAND ${CMAKE_COMMAND} "-DCMD=$<TARGET_FILE:clpath>;${T_ARGS}" -DEXPECT_FAIL=${fail} -DEXPECT_RC=${T_RC}
                     "-DEXPECT_OUTPUT=${T_OUTPUT}" "-DREJECT_OUTPUT=${T_REJECT}" -DFORBID_FILE=${T_FORBID} -DEXPECT_FILE=${T_MAKES}
                     -P ${CMAKE_CURRENT_SOURCE_DIR}/cli/expect.cmake)
    set_tests_properties(cli.usage.${name} PROPERTIES ENVIRONMENT "${CLPATH_TEST_ENV};${T_ENV}" TIMEOUT 300)
endfunction()

set(SMALL --spp 1 --width 16 --height 12)

# --- argument parsing: the CLI11 errors in the one form ------------------------------------
clpath_usage_test(unknown_option RC 2 ARGS render --bogus
                  OUTPUT "^clpath: error: The following argument was not expected: --bogus.*see 'clpath render --help'")
clpath_usage_test(missing_value RC 2 ARGS render --spp
                  OUTPUT "^clpath: error: --spp: 1 required UINT:INT in \\[1, 4294967295\\] missing")
clpath_usage_test(no_subcommand RC 2 ARGS "" OUTPUT "^clpath: error: A subcommand is required\n\\(see 'clpath --help'\\)")
clpath_usage_test(missing_positional RC 2 ARGS compare OUTPUT "^clpath: error: image is required")
clpath_usage_test(help_is_not_an_error RC 0 ARGS render --help OUTPUT "--tonemap")
# Every command that takes a scene loads what render loads, and says so.
foreach(cmd view export bench_rays bench_build bench_convergence)
    string(REPLACE "_" ";" words ${cmd})
    clpath_usage_test(${cmd}_help_names_scene_kinds RC 0 ARGS ${words} --help
                      OUTPUT "glTF model \\(\\.gltf, \\.glb\\) or built-in scene \\(cornell, scaling:N, room:N, bunnies:N, city:N\\)")
endforeach()

# --- numbers: non-finite, negative, out of range ---------------------------------------------
clpath_usage_test(time_nan RC 2 ARGS render --time nan
                  OUTPUT "^clpath: error: --time: 'nan' is not a finite number above 0 and up to 31536000")
clpath_usage_test(time_inf RC 2 ARGS render --time inf OUTPUT "^clpath: error: --time: 'inf' is not a finite number above 0 and up to 31536000")
clpath_usage_test(time_negative RC 2 ARGS render --time -1 OUTPUT "^clpath: error: --time: '-1' is not a finite number above 0 and up to 31536000")
clpath_usage_test(time_zero RC 2 ARGS render --time 0 OUTPUT "^clpath: error: --time: '0' is not a finite number above 0 and up to 31536000")
clpath_usage_test(time_overflow RC 2 ARGS render --time 1e999 OUTPUT "^clpath: error: --time: '1e999' is not a finite number above 0 and up to 31536000")
clpath_usage_test(seed_negative RC 2 ARGS render --seed -1
                  OUTPUT "^clpath: error: --seed: '-1' is not a whole number from 0 to 4294967295")
clpath_usage_test(seed_too_large RC 2 ARGS render --seed 4294967296
                  OUTPUT "^clpath: error: --seed: '4294967296' is not a whole number from 0 to 4294967295")
clpath_usage_test(seed_fraction RC 2 ARGS render --seed 1.5 OUTPUT "^clpath: error: --seed: '1\\.5' is not a whole number from 0 to 4294967295")
clpath_usage_test(spp_zero RC 2 ARGS render --spp 0 OUTPUT "^clpath: error: --spp: '0' is not a whole number from 1 to 4294967295")
clpath_usage_test(spp_negative RC 2 ARGS render --spp -4 OUTPUT "^clpath: error: --spp: '-4' is not a whole number from 1 to 4294967295")
clpath_usage_test(width_zero RC 2 ARGS render --width 0 OUTPUT "^clpath: error: --width: '0' is not a whole number from 1 to 16384")
clpath_usage_test(height_huge RC 2 ARGS render --height 20000 OUTPUT "^clpath: error: --height: '20000' is not a whole number from 1 to 16384")
clpath_usage_test(max_depth_too_deep RC 2 ARGS render --max-depth 2000 OUTPUT "^clpath: error: --max-depth: '2000' is not a whole number from 0 to 1024")
clpath_usage_test(ao_distance_nan RC 2 ARGS render --ao-distance nan OUTPUT "^clpath: error: --ao-distance: 'nan' is not a finite number above 0 and up to 1000000000")
clpath_usage_test(leaf_size_zero RC 2 ARGS render --leaf-size 0 OUTPUT "^clpath: error: --leaf-size: '0' is not a whole number from 1 to 64")
clpath_usage_test(exposure_out_of_range RC 2 ARGS render --exposure 30 OUTPUT "^clpath: error: --exposure: '30' is not a finite number from -20 to 20")
clpath_usage_test(exposure_nan RC 2 ARGS render --exposure nan OUTPUT "^clpath: error: --exposure: 'nan' is not a finite number from -20 to 20")
clpath_usage_test(light_sampler_unknown RC 2 ARGS render --light-sampler tree OUTPUT "^clpath: error: --light-sampler: tree not in \\{auto,power,bvh\\}")
clpath_usage_test(tonemap_unknown RC 2 ARGS render --tonemap filmic OUTPUT "^clpath: error: --tonemap: filmic not in \\{clamp,reinhard,aces\\}")
clpath_usage_test(export_width_negative RC 2 ARGS export cornell ${USAGE_OUT}/width-negative.json --width -3 OUTPUT "^clpath: error: --width: '-3' is not a whole number from 1 to 16384")
clpath_usage_test(compare_clamp_inf RC 2 ARGS compare ${CLI_DATA}/yz-plate.obj ${CLI_DATA}/yz-plate.obj --clamp inf
                  OUTPUT "^clpath: error: --clamp: 'inf' is not a finite number above 0 and up to 1000000000")
clpath_usage_test(view_seed_negative RC 2 ARGS view --seed -1 OUTPUT "^clpath: error: --seed: '-1' is not a whole number from 0 to 4294967295")
clpath_usage_test(bench_rays_seed_negative RC 2 ARGS bench rays --seed -2 OUTPUT "^clpath: error: --seed: '-2' is not a whole number from 0 to 4294967295")
clpath_usage_test(bench_convergence_time_cap_nan RC 2 ARGS bench convergence cornell --time-cap nan
                  OUTPUT "^clpath: error: --time-cap: 'nan' is not a finite number above 0 and up to 1000000000")

# --- devices: by type, and the environment ------------------------------------------------
clpath_usage_test(device_cpu RC 0 ARGS render ${SMALL} --device cpu -o ${USAGE_OUT}/cpu.pfm OUTPUT "summary: .*nonfinite=0 accel=bvh")
clpath_usage_test(device_cpu_from_env RC 0 ENV CLPATH_DEVICE=CPU ARGS render ${SMALL} -o ${USAGE_OUT}/cpu-env.pfm
                  OUTPUT "summary: ")
# The control: the variable is read (a GPU asked for through it is refused, by name).
clpath_usage_test(device_gpu_from_env_when_none RC 2 ENV CLPATH_DEVICE=gpu ARGS render ${SMALL} -o ${USAGE_OUT}/gpu-env.pfm
                  OUTPUT "clpath: error: CLPATH_DEVICE gpu: no GPU device\\. Devices:" FORBID ${USAGE_OUT}/gpu-env.pfm)
# The test machines have no GPU; where one exists, the test says nothing.
clpath_usage_test(device_gpu_when_none RC 2 ARGS render ${SMALL} --device gpu -o ${USAGE_OUT}/gpu.pfm
                  OUTPUT "^.*clpath: error: --device gpu: no GPU device\\. Devices:" FORBID ${USAGE_OUT}/gpu.pfm)
clpath_usage_test(device_index_names_range RC 2 ARGS render ${SMALL} --device 7 -o ${USAGE_OUT}/idx.pfm
                  OUTPUT "clpath: error: --device 7: no device with that index \\(the indices are 0 to [0-9]+\\)")
clpath_usage_test(memory_limit_not_a_number RC 2 ENV CLPATH_DEVICE_MEMORY_LIMIT=abc ARGS render ${SMALL} -o ${USAGE_OUT}/mem.pfm
                  OUTPUT "clpath: error: CLPATH_DEVICE_MEMORY_LIMIT='abc': expected a whole number of bytes from 1 to 18446744073709551615"
                  FORBID ${USAGE_OUT}/mem.pfm)
clpath_usage_test(memory_limit_negative RC 2 ENV CLPATH_DEVICE_MEMORY_LIMIT=-5 ARGS render ${SMALL} -o ${USAGE_OUT}/mem2.pfm
                  OUTPUT "clpath: error: CLPATH_DEVICE_MEMORY_LIMIT='-5': expected a whole number of bytes from 1 to 18446744073709551615")
clpath_usage_test(memory_limit_zero RC 2 ENV CLPATH_DEVICE_MEMORY_LIMIT=0 ARGS render ${SMALL} -o ${USAGE_OUT}/mem3.pfm
                  OUTPUT "clpath: error: CLPATH_DEVICE_MEMORY_LIMIT='0': expected a whole number of bytes from 1 to 18446744073709551615")
clpath_usage_test(progress_interval_not_a_number RC 2 ENV CLPATH_PROGRESS_INTERVAL_MS=1.5 ARGS render ${SMALL} -o ${USAGE_OUT}/pi-fraction.pfm
                  OUTPUT "clpath: error: CLPATH_PROGRESS_INTERVAL_MS='1\\.5': expected a whole number of milliseconds from 10 to 86400000"
                  FORBID ${USAGE_OUT}/pi-fraction.pfm)
clpath_usage_test(progress_interval_too_short RC 2 ENV CLPATH_PROGRESS_INTERVAL_MS=0 ARGS render ${SMALL} -o ${USAGE_OUT}/pi-zero.pfm
                  OUTPUT "clpath: error: CLPATH_PROGRESS_INTERVAL_MS='0': expected a whole number of milliseconds from 10 to 86400000")

# --- outputs --------------------------------------------------------------------------------
clpath_usage_test(out_is_folder_with_slash RC 2 ARGS render ${SMALL} -o ${A_FOLDER}/
                  OUTPUT "clpath: error: output .*a-folder/: is a folder; name an image file in it, such as .*a-folder/image\\.png")
clpath_usage_test(out_is_existing_folder RC 2 ARGS render ${SMALL} -o ${A_FOLDER}
                  OUTPUT "clpath: error: output .*a-folder: is a folder")
clpath_usage_test(out_folder_missing RC 2 ARGS render ${SMALL} -o ${USAGE_OUT}/nowhere/x.png
                  OUTPUT "clpath: error: output .*nowhere/x\\.png: folder .*nowhere does not exist")
clpath_usage_test(out_unknown_format RC 2 ARGS render ${SMALL} -o ${USAGE_OUT}/x.tiff
                  OUTPUT "clpath: error: output .*x\\.tiff: unknown image format '\\.tiff' \\(use \\.png, \\.exr or \\.pfm\\)")
# A run that fails (not bad usage) exits 1.
clpath_usage_test(bad_scene_file_is_a_failed_run RC 1 ARGS render ${CMAKE_CURRENT_SOURCE_DIR}/scene/data/malformed.json ${SMALL}
                  -o ${USAGE_OUT}/malformed.pfm OUTPUT "^clpath: error: .*malformed\\.json:4:31: syntax error")

# --- display: exposure and tone mapping for PNG; float outputs linear ----------------------
clpath_usage_test(tonemap_aces_png RC 0 ARGS render ${SMALL} --tonemap aces --exposure 1.5 -o ${USAGE_OUT}/aces.png
                  MAKES ${USAGE_OUT}/aces.png OUTPUT "wrote .*aces\\.png")
clpath_usage_test(tonemap_reinhard_png RC 0 ARGS render ${SMALL} --tonemap reinhard -o ${USAGE_OUT}/reinhard.png
                  MAKES ${USAGE_OUT}/reinhard.png OUTPUT "wrote .*reinhard\\.png")

# --- camera and environment overrides -----------------------------------------------------
clpath_usage_test(camera_one_field RC 0 ARGS render ${SMALL} --camera fov=30 -o ${USAGE_OUT}/fov.pfm OUTPUT "summary: ")
clpath_usage_test(camera_unknown_field RC 2 ARGS render ${SMALL} --camera zoom=2 -o ${USAGE_OUT}/cam-unknown.pfm
                  OUTPUT "clpath: error: --camera 'zoom': unknown field \\(choose from from, to, fov, up, aperture, focus\\)")
clpath_usage_test(camera_thin_lens RC 0 ARGS render ${SMALL} --camera aperture=0.05 -o ${USAGE_OUT}/lens.pfm
                  OUTPUT "summary: ")
clpath_usage_test(camera_negative_aperture RC 2 ARGS render ${SMALL} --camera aperture=-1 -o ${USAGE_OUT}/cam-ap.pfm
                  OUTPUT "clpath: error: --camera aperture=-1: the lens radius must be a number >= 0 \\(0: a pinhole\\)")
clpath_usage_test(camera_zero_focus RC 2 ARGS render ${SMALL} --camera focus=0 -o ${USAGE_OUT}/cam-focus.pfm
                  OUTPUT "clpath: error: --camera focus=0: the focus distance must be a number > 0")
clpath_usage_test(camera_bad_number RC 2 ARGS render ${SMALL} --camera from=0,nan,1 -o ${USAGE_OUT}/cam-nan.pfm
                  OUTPUT "clpath: error: --camera from=0,nan,1: 'nan' is not a finite number")
clpath_usage_test(camera_fov_range RC 2 ARGS render ${SMALL} --camera fov=180 -o ${USAGE_OUT}/cam-fov.pfm
                  OUTPUT "clpath: error: --camera fov=180: the vertical field of view must be a number of degrees from 1 to 179")
clpath_usage_test(camera_no_equals RC 2 ARGS render ${SMALL} --camera 1,2,3 -o ${USAGE_OUT}/cam-no-equals.pfm
                  OUTPUT "clpath: error: --camera '1,2,3': expected NAME=VALUE")
# A bundled CC0 HDRI (OpenEXR) as the environment of a bare mesh and of a scene file.
clpath_usage_test(env_exr_bare_mesh RC 0 ARGS render ${CMAKE_SOURCE_DIR}/scenes/suzanne/Suzanne.gltf ${SMALL}
                  --env ${CMAKE_SOURCE_DIR}/scenes/hdri/studio.exr -o ${USAGE_OUT}/env-exr.pfm
                  MAKES ${USAGE_OUT}/env-exr.pfm OUTPUT "summary: ")
clpath_usage_test(env_missing_file RC 2 ARGS render ${SMALL} --env ${USAGE_OUT}/no-sky.hdr -o ${USAGE_OUT}/env-missing.pfm
                  OUTPUT "clpath: error: --env .*no-sky\\.hdr: no such file")
clpath_usage_test(env_negative_colour RC 2 ARGS render ${SMALL} --env -1,0,0 -o ${USAGE_OUT}/env-negative.pfm
                  OUTPUT "clpath: error: --env -1,0,0: a colour's channels must be from 0 to 1000000")
clpath_usage_test(env_colour RC 0 ARGS render ${CLI_DATA}/yz-plate.obj ${SMALL} --env 0.5 -o ${USAGE_OUT}/env-grey.pfm
                  OUTPUT "summary: ")
clpath_usage_test(no_ground_on_builtin_warns RC 0 ARGS render ${SMALL} --no-ground -o ${USAGE_OUT}/ng.pfm
                  OUTPUT "warning: --no-ground has no effect on cornell: only a bare mesh gets a ground")
# A bare glTF model is presented as a bare OBJ is, with the same overrides.
set(SUZANNE ${CMAKE_SOURCE_DIR}/scenes/suzanne/Suzanne.gltf)
clpath_usage_test(no_ground_on_gltf RC 0 ARGS render ${SUZANNE} ${SMALL} --no-ground -o ${USAGE_OUT}/ng-gltf.pfm
                  OUTPUT "summary: .*triangles=3936 " REJECT "no effect")  # the model's own triangles only
clpath_usage_test(env_on_gltf_replaces_sky_and_sun RC 0 ARGS render ${SUZANNE} ${SMALL} --env 0 -o ${USAGE_OUT}/env-gltf.pfm
                  OUTPUT "scene 'Suzanne' has no emitter; the image will be black")
clpath_usage_test(gltf_has_sky_and_sun RC 0 ARGS render ${SUZANNE} ${SMALL} -o ${USAGE_OUT}/sky-gltf.pfm
                  OUTPUT "summary: .*triangles=3938 " REJECT "no emitter")  # the control for the two above
# The presentation chosen, and why, is said on stderr.
clpath_usage_test(gltf_presentation_says_why RC 0 ARGS render ${SUZANNE} ${SMALL} -o ${USAGE_OUT}/why-gltf.pfm
                  OUTPUT "clpath: presentation: the model brings no light, so a sky, a sun and a ground are added")
clpath_usage_test(gltf_presentation_env_says_why RC 0 ARGS render ${SUZANNE} ${SMALL} --env 0.5 -o ${USAGE_OUT}/why-env.pfm
                  OUTPUT "clpath: presentation: the environment given lights the model" REJECT "brings no light")
clpath_usage_test(camera_on_gltf RC 0 ARGS render ${SUZANNE} ${SMALL} --camera from=0,0,-9
                  -o ${USAGE_OUT}/cam-gltf.pfm OUTPUT "summary: ")

# --- --gltf-camera: a glTF file's camera by name or index -------------------------------------
# two-cameras.gltf: camera 0 'front' faces the square, camera 1 'side' sees it edge-on.
set(TWO_CAMERAS ${CLI_DATA}/two-cameras.gltf)
file(REMOVE ${USAGE_OUT}/gltf-cam-name.pfm ${USAGE_OUT}/gltf-cam-index.pfm)
clpath_usage_test(gltf_camera_by_name RC 0 ARGS render ${TWO_CAMERAS} ${SMALL} --gltf-camera side --no-ground
                  -o ${USAGE_OUT}/gltf-cam-name.pfm MAKES ${USAGE_OUT}/gltf-cam-name.pfm OUTPUT "summary: .*triangles=2 ")
clpath_usage_test(gltf_camera_by_index RC 0 ARGS render ${TWO_CAMERAS} ${SMALL} --gltf-camera 1 --no-ground
                  -o ${USAGE_OUT}/gltf-cam-index.pfm MAKES ${USAGE_OUT}/gltf-cam-index.pfm OUTPUT "summary: .*triangles=2 ")
# The name and the index choose the same camera: the same image, bit for bit; the
# control (the other camera) must differ, or the comparison could not tell.
string(REPLACE ";" " " SMALL_TEXT "${SMALL}")
set(GLTF_RENDER "$<TARGET_FILE:clpath> render ${TWO_CAMERAS} ${SMALL_TEXT} -q --gltf-camera")
add_test(NAME cli.usage.gltf_camera_name_and_index_agree
         COMMAND ${CMAKE_COMMAND}
                 "-DCMDS=${GLTF_RENDER} side -o ${USAGE_OUT}/gc-side.pfm|${GLTF_RENDER} 1 -o ${USAGE_OUT}/gc-1.pfm"
                 "-DOUTS=${USAGE_OUT}/gc-side.pfm;${USAGE_OUT}/gc-1.pfm" -P ${CMAKE_CURRENT_SOURCE_DIR}/cli/same_image.cmake)
add_test(NAME cli.usage.gltf_camera_control_other_camera_differs
         COMMAND ${CMAKE_COMMAND}
                 "-DCMDS=${GLTF_RENDER} front -o ${USAGE_OUT}/gc-front.pfm|${GLTF_RENDER} 1 -o ${USAGE_OUT}/gc-1b.pfm"
                 "-DOUTS=${USAGE_OUT}/gc-front.pfm;${USAGE_OUT}/gc-1b.pfm" -P ${CMAKE_CURRENT_SOURCE_DIR}/cli/same_image.cmake)
set_tests_properties(cli.usage.gltf_camera_name_and_index_agree cli.usage.gltf_camera_control_other_camera_differs
                     PROPERTIES ENVIRONMENT "${CLPATH_TEST_ENV}" TIMEOUT 300)
# Passes only on the comparison's own failure message (a failed render would not print it).
set_tests_properties(cli.usage.gltf_camera_control_other_camera_differs PROPERTIES PASS_REGULAR_EXPRESSION
                     "gc-1b\\.pfm differs from")
clpath_usage_test(gltf_camera_unknown_name RC 2 ARGS render ${TWO_CAMERAS} ${SMALL} --gltf-camera top
                  -o ${USAGE_OUT}/gltf-cam-top.pfm FORBID ${USAGE_OUT}/gltf-cam-top.pfm
                  OUTPUT "^clpath: error: --gltf-camera: .*two-cameras\\.gltf: no camera 'top' placed by a node \\(cameras: 0 'front', 1 'side'\\)")
clpath_usage_test(gltf_camera_index_out_of_range RC 2 ARGS render ${TWO_CAMERAS} ${SMALL} --gltf-camera 2
                  -o ${USAGE_OUT}/gltf-cam-2.pfm FORBID ${USAGE_OUT}/gltf-cam-2.pfm
                  OUTPUT "^clpath: error: --gltf-camera: .*two-cameras\\.gltf: no camera '2' placed by a node \\(cameras: 0 'front', 1 'side'\\)")

# --- export ---------------------------------------------------------------------------------
file(REMOVE_RECURSE ${USAGE_OUT}/export-made)
clpath_usage_test(export_creates_folder RC 0 ARGS export cornell ${USAGE_OUT}/export-made/deeper/c.json
                  MAKES ${USAGE_OUT}/export-made/deeper/c.obj OUTPUT "wrote .*export-made/deeper/c\\.json")
clpath_usage_test(export_help_names_materials RC 0 ARGS export --help
                  OUTPUT "--format obj \\(the default\\) exports diffuse materials, emitters.*refuses.*mirror, conductor")
clpath_usage_test(export_wrong_extension RC 2 ARGS export cornell ${USAGE_OUT}/c.txt
                  OUTPUT "clpath: error: output .*c\\.txt: must end in \\.json")
clpath_usage_test(export_refuses_mirror RC 1 ARGS export ${CLI_DATA}/mirror.json ${USAGE_OUT}/never/m.json
                  OUTPUT "clpath: error: .*mirror\\.json: cannot export: .*mirror" FORBID ${USAGE_OUT}/never)

# --- real OBJ files load as other tools load them ------------------------------------------
clpath_usage_test(obj_missing_mtl_warns RC 0 ARGS render ${CLI_DATA}/missing-mtl.obj ${SMALL} -o ${USAGE_OUT}/mtl.pfm
                  OUTPUT "warning: .*missing-mtl\\.obj:2: mtllib 'not-here\\.mtl': .*no such file; the materials it would define are the default grey.*warning: .*missing-mtl\\.obj:6: usemtl 'paint': no \\.mtl file defines it; it is the default grey")
clpath_usage_test(obj_unused_channel_warns RC 0 ARGS render ${CLI_DATA}/glass-ni0.obj ${SMALL} -o ${USAGE_OUT}/ni0.pfm
                  OUTPUT "warning: .*glass-ni0\\.mtl: material 'plastic': Ni 0\\.0+ is out of range .*; the material does not use it, so it is ignored")
clpath_usage_test(obj_mtl_bad_number RC 1 ARGS render ${CLI_DATA}/bad-ns.obj ${SMALL} -o ${USAGE_OUT}/ns.pfm
                  OUTPUT "^clpath: error: .*bad-ns\\.mtl:3: Ns: 'abc' is not a number" FORBID ${USAGE_OUT}/ns.pfm)


# --- usage errors that were accepted or exited 1 --------------------------------------------
clpath_usage_test(device_empty RC 2 ARGS render ${SMALL} --device EMPTY_ARG -o ${USAGE_OUT}/dev-empty.pfm
                  OUTPUT "^clpath: error: --device: an empty value; give a device index or name, cpu, gpu or all")
clpath_usage_test(bench_device_empty RC 2 ARGS bench rays cornell --quick --device EMPTY_ARG
                  OUTPUT "^clpath: error: --device: an empty value; give a device index or name")
clpath_usage_test(device_twice RC 2 ARGS render ${SMALL} --device 0,0 -o ${USAGE_OUT}/dev-twice.pfm FORBID ${USAGE_OUT}/dev-twice.pfm
                  OUTPUT "clpath: error: --device '0,0': device \\[0\\] .* is named twice \\('0'\\)")
clpath_usage_test(device_empty_item RC 2 ARGS render ${SMALL} --device 0,,0 -o ${USAGE_OUT}/dev-item.pfm
                  OUTPUT "clpath: error: --device '0,,0': an empty item in the device list")
clpath_usage_test(env_not_an_image RC 2 ARGS render ${SMALL} --env ${CLI_DATA}/not-an-image.png -o ${USAGE_OUT}/env-text.pfm
                  FORBID ${USAGE_OUT}/env-text.pfm OUTPUT "clpath: error: --env .*not-an-image\\.png: cannot read .*not-an-image\\.png as an image")
clpath_usage_test(gltf_camera_on_obj RC 2 ARGS render ${CLI_DATA}/yz-plate.obj ${SMALL} --gltf-camera 0 -o ${USAGE_OUT}/gc-obj.pfm
                  FORBID ${USAGE_OUT}/gc-obj.pfm OUTPUT "^clpath: error: --gltf-camera 0: .*yz-plate\\.obj is not a glTF model")
clpath_usage_test(gltf_camera_on_builtin RC 2 ARGS render cornell ${SMALL} --gltf-camera front -o ${USAGE_OUT}/gc-b.pfm
                  OUTPUT "^clpath: error: --gltf-camera front: cornell is not a glTF model")
clpath_usage_test(gltf_camera_empty RC 2 ARGS render ${TWO_CAMERAS} ${SMALL} --gltf-camera EMPTY_ARG -o ${USAGE_OUT}/gc-e.pfm
                  OUTPUT "^clpath: error: --gltf-camera: an empty value; give a camera's name or index")
