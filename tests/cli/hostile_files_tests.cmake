# Hostile and real-world files through the program a user runs: each is
# refused with its own message naming the file and field (a pattern that
# "clpath: error:" alone cannot satisfy), or loads, with a control beside it.
# clpath_usage_test comes from usage_tests.cmake.
set(HOSTILE ${CMAKE_CURRENT_SOURCE_DIR}/cli/data/hostile)
set(FUZZ_KEPT ${CMAKE_CURRENT_SOURCE_DIR}/fuzz/regressions/gltf)
set(HOSTILE_OUT ${CMAKE_BINARY_DIR}/cli-hostile-out)
file(MAKE_DIRECTORY ${HOSTILE_OUT})
set(TINY --spp 1 --width 16 --height 12)

# --- parsing that cannot be driven into recursion or combinatorial work --------------------
clpath_usage_test(gltf_deep_extras_refused RC 1 ARGS render ${FUZZ_KEPT}/extras-nested-20000-deep-overflowed-the-stack.gltf
                  ${TINY} -o ${HOSTILE_OUT}/deep.pfm FORBID ${HOSTILE_OUT}/deep.pfm
                  OUTPUT "^clpath: error: .*extras-nested-20000-deep-overflowed-the-stack\\.gltf: the JSON nests arrays and objects deeper than 512 levels")
clpath_usage_test(gltf_node_paths_refused RC 1 ARGS render ${FUZZ_KEPT}/child-listed-twice-40-deep-2pow40-paths-hung.gltf
                  ${TINY} -o ${HOSTILE_OUT}/dag.pfm FORBID ${HOSTILE_OUT}/dag.pfm
                  OUTPUT "^clpath: error: .*2pow40-paths-hung\\.gltf: scenes\\[0\\]\\.nodes: the node hierarchy places more than 1000000 nodes.*the limit is 1000000 placed nodes")
set_tests_properties(cli.usage.gltf_node_paths_refused PROPERTIES TIMEOUT 60)

# --- what tinygltf accepted silently ----------------------------------------------------------
clpath_usage_test(glb_header_version_3 RC 1 ARGS render ${HOSTILE}/glb-version-3.glb ${TINY} -o ${HOSTILE_OUT}/v3.pfm
                  OUTPUT "^clpath: error: .*glb-version-3\\.glb: GLB header: version 3 is not supported \\(a binary glTF 2\\.0 file has version 2\\)")
clpath_usage_test(gltf_asset_version_3 RC 1 ARGS render ${HOSTILE}/asset-version-3.gltf ${TINY} -o ${HOSTILE_OUT}/a3.pfm
                  OUTPUT "^clpath: error: .*asset-version-3\\.gltf: asset\\.version: '3\\.0' is not supported")
clpath_usage_test(gltf_default_scene_missing RC 1 ARGS render ${HOSTILE}/scenes-empty-scene-0.gltf ${TINY} -o ${HOSTILE_OUT}/s0.pfm
                  OUTPUT "^clpath: error: .*scenes-empty-scene-0\\.gltf: scene: scene 0 does not exist \\(the file has 0\\)")
clpath_usage_test(gltf_aspect_ratio_zero RC 1 ARGS render ${HOSTILE}/aspect-ratio-0.gltf ${TINY} -o ${HOSTILE_OUT}/ar0.pfm
                  OUTPUT "^clpath: error: .*aspect-ratio-0\\.gltf: cameras\\[0\\]\\.perspective\\.aspectRatio: 0 is out of range \\(must be above 0\\)")
clpath_usage_test(gltf_aspect_ratio_negative RC 1 ARGS render ${HOSTILE}/aspect-ratio-negative.gltf ${TINY} -o ${HOSTILE_OUT}/arn.pfm
                  OUTPUT "^clpath: error: .*aspect-ratio-negative\\.gltf: cameras\\[0\\]\\.perspective\\.aspectRatio: -1\\.5 is out of range")
clpath_usage_test(gltf_light_intensity_text RC 1 ARGS render ${HOSTILE}/light-intensity-string.gltf ${TINY} -o ${HOSTILE_OUT}/li.pfm
                  OUTPUT "^clpath: error: .*light-intensity-string\\.gltf: extensions\\.KHR_lights_punctual\\.lights\\[0\\]\\.intensity: expected a number, got a string \\(\"bright\"\\)")

# --- real files that must load (a neutral stand-in and a warning where something is missing) ---
clpath_usage_test(gltf_orthographic_camera RC 0 ARGS render ${HOSTILE}/orthographic-camera.gltf ${TINY} -o ${HOSTILE_OUT}/ortho.pfm
                  MAKES ${HOSTILE_OUT}/ortho.pfm OUTPUT "summary: "
                  REJECT "error")
clpath_usage_test(gltf_orthographic_camera_overridden RC 0 ARGS render ${HOSTILE}/orthographic-camera.gltf ${TINY}
                  --camera fov=40 -o ${HOSTILE_OUT}/ortho-cam.pfm MAKES ${HOSTILE_OUT}/ortho-cam.pfm)
clpath_usage_test(gltf_skin_rest_pose RC 0 ARGS render ${HOSTILE}/skin-without-inverse-bind-matrices.gltf ${TINY}
                  -o ${HOSTILE_OUT}/skin.pfm MAKES ${HOSTILE_OUT}/skin.pfm
                  OUTPUT "clpath: warning: .*skin-without-inverse-bind-matrices\\.gltf: 1 skin: not evaluated; the meshes are loaded in their rest pose")
clpath_usage_test(obj_missing_map_kd RC 0 ARGS render ${HOSTILE}/missing-map.obj ${TINY} -o ${HOSTILE_OUT}/map.pfm
                  MAKES ${HOSTILE_OUT}/map.pfm
                  OUTPUT "clpath: warning: .*missing-map\\.mtl:4: map_Kd of material 'wood': .*hostile/textures/wood\\.png: no such file; the material is rendered without it")

# --- --restrict-files: canaries reached through "..", %2F, a link, an absolute path, a .glb's uri -
add_test(NAME cli.hostile.restrict_files
         COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/cli/restrict_files.sh $<TARGET_FILE:clpath> ${HOSTILE_OUT}/restrict)
set_tests_properties(cli.hostile.restrict_files PROPERTIES ENVIRONMENT "${CLPATH_TEST_ENV}" TIMEOUT 300)
