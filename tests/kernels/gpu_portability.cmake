# The portability gate: every program clpath can build (the covering set of
# render/kernel_programs.hpp and the programs of every bundled scene), as it is
# built for a GPU device, compiled offline for NVIDIA sm_90 and AMD gfx90a and
# gfx1100 (clpath kernels --report --check, cl/offline_compile.hpp). A test
# fails on a compile error, an unresolved symbol or a traversal kernel over
# its register or stack budget; it is skipped (exit 77, naming what is
# missing) where its target's tools are not installed, never passed without
# compiling. One test per target, so ctest spreads them; results are cached in
# the build folder per source, options, target and tools.
file(GLOB_RECURSE CLPATH_BUNDLED_SCENES CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/scenes/*.json ${CMAKE_SOURCE_DIR}/scenes/*.gltf)
set(GPU_COMPILE_CACHE ${CMAKE_BINARY_DIR}/gpu-compile-cache)
# gfx1100 compiles the bundled scenes' programs only (CI's time: the covering
# set there is compiled by benchmarks/gpu-compile/run.sh).
foreach(target sm_90 gfx90a gfx1100)
    set(covering --covering cornell)
    if(target STREQUAL "gfx1100")
        set(covering "")
    endif()
    add_test(NAME gpu_portability.${target}
             COMMAND $<TARGET_FILE:clpath> kernels --report --check --targets ${target} --jobs 1
                     --cache ${GPU_COMPILE_CACHE} ${covering} ${CLPATH_BUNDLED_SCENES})
    set_tests_properties(gpu_portability.${target} PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 1800
                         LABELS "gpu-portability;slow")
endforeach()

# The control: the same gate over kernels where normalize3 is a plain C99
# inline function kept out of line (the bug the gate exists for) must report
# it as an unresolved symbol on every target.
set(GPU_CONTROL_KERNELS ${CMAKE_BINARY_DIR}/gpu-portability-control)
set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/kernels/common.h)
file(READ ${CMAKE_SOURCE_DIR}/kernels/common.h CLPATH_COMMON_H)
string(REPLACE "static inline float3 normalize3(" "__attribute__((noinline)) inline float3 normalize3("
       CLPATH_COMMON_H_BROKEN "${CLPATH_COMMON_H}")
if(CLPATH_COMMON_H_BROKEN STREQUAL CLPATH_COMMON_H)
    message(FATAL_ERROR "tests/kernels/gpu_portability.cmake: kernels/common.h no longer defines "
                        "'static inline float3 normalize3(': update the control")
endif()
file(MAKE_DIRECTORY ${GPU_CONTROL_KERNELS})
file(WRITE ${GPU_CONTROL_KERNELS}/common.h "${CLPATH_COMMON_H_BROKEN}")
foreach(target sm_90 gfx90a gfx1100)
    add_test(NAME gpu_portability.control_${target}
             COMMAND $<TARGET_FILE:clpath> kernels --report --check --targets ${target} --jobs 1
                     --kernels ${GPU_CONTROL_KERNELS} cornell)
    set_tests_properties(gpu_portability.control_${target} PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 600
                         LABELS "gpu-portability"
                         PASS_REGULAR_EXPRESSION "for ${target} [^\n]*\nunresolved symbols after linking libclc:[^\n]* normalize3")
endforeach()

# Both codes of the kernels (kernel_programs.hpp) run on both OpenCL implementations: PoCL (a CPU
# device, which gets the CPU code) with the GPU code, and Oclgrind (which
# calls itself a GPU) with the CPU code. On PoCL the GPU code must give the
# CPU code's answers bit for bit (bench rays, each batch also checked against
# its double-precision CPU traversal) and the same image (bench render-ab; a
# scene with every material, light and environment kind, the textured
# scene with its alpha-masked fence, and the instanced bunnies, whose GPU
# walk is one loop over both levels and the CPU's two).
# (The flat list of object boxes on the Cornell box: on bunny's one object it
# would test every triangle for every ray.)
foreach(accel_scene bvh:${CMAKE_SOURCE_DIR}/scenes/bunny.json flat:cornell)
    string(REGEX REPLACE ":.*" "" accel ${accel_scene})
    string(REGEX REPLACE "^[a-z]+:" "" scene ${accel_scene})
    add_test(NAME kernel_code.gpu_on_pocl_bench_rays.${accel}
             COMMAND $<TARGET_FILE:clpath> bench rays ${scene} --accel ${accel} --quick --no-embree
                     --ab-options=-DCLP_TARGET_GPU)
    set_tests_properties(kernel_code.gpu_on_pocl_bench_rays.${accel} PROPERTIES ENVIRONMENT "${CLPATH_TEST_ENV}"
        LABELS "render" TIMEOUT 600 PASS_REGULAR_EXPRESSION
        "primary: [0-9]+ rays [^\n]* 0 mismatched[^\n]*\n  A/B: [^\n]*answers differ for 0 rays\nshadow: [0-9]+ rays [^\n]* 0 mismatched[^\n]*\n  A/B: [^\n]*answers differ for 0 rays\ndiffuse: [0-9]+ rays [^\n]* 0 mismatched[^\n]*\n  A/B: [^\n]*answers differ for 0 rays")
endforeach()
foreach(scene kernels/data/oclgrind-features.json ../scenes/textured/textured.json ../scenes/bunny-instances.json)
    get_filename_component(name ${scene} NAME_WE)
    add_test(NAME kernel_code.gpu_on_pocl_render.${name}
             COMMAND $<TARGET_FILE:clpath> bench render-ab ${CMAKE_CURRENT_SOURCE_DIR}/${scene} --spp 2 --width 32
                     --height 24 --ab-options=-DCLP_TARGET_GPU)
    set_tests_properties(kernel_code.gpu_on_pocl_render.${name} PROPERTIES ENVIRONMENT "${CLPATH_TEST_ENV}"
                         LABELS "render" TIMEOUT 600 PASS_REGULAR_EXPRESSION "images differ in 0 of 768 pixels")
    # The wavefront in GPU code, as GPUs run it, against the megakernel in CPU code.
    add_test(NAME kernel_code.gpu_wavefront_on_pocl_render.${name}
             COMMAND $<TARGET_FILE:clpath> bench render-ab ${CMAKE_CURRENT_SOURCE_DIR}/${scene} --spp 2 --width 32
                     --height 24 --ab-shape wavefront --ab-options=-DCLP_TARGET_GPU)
    set_tests_properties(kernel_code.gpu_wavefront_on_pocl_render.${name} PROPERTIES ENVIRONMENT "${CLPATH_TEST_ENV}"
                         LABELS "render" TIMEOUT 600 PASS_REGULAR_EXPRESSION
                         "variant \\(wavefront\\)[^\n]*images differ in 0 of 768 pixels")
endforeach()
if(OCLGRIND)
    foreach(integrator path ao)
        clpath_oclgrind_test(cpu_code.render.${integrator} OPTIONS ${OCLGRIND_BASIC}
                             COMMAND $<TARGET_FILE:clpath> render ${OCLGRIND_SCENE} --all-features -i ${integrator}
                                     -q -o ${OCLGRIND_LOGS}/cpu-code-render-${integrator}.pfm
                             OUTPUT "device=\"Oclgrind Simulator\" .*integrator=${integrator} .*nonfinite=0")
        set_tests_properties(oclgrind.cpu_code.render.${integrator} PROPERTIES
                             ENVIRONMENT "CLPATH_CACHE_DIR=off;CLPATH_KERNEL_CODE=cpu")
    endforeach()
    clpath_oclgrind_test(cpu_code.bench_rays.bvh OPTIONS ${OCLGRIND_STRICT}
                         COMMAND $<TARGET_FILE:clpath> bench rays ${OCLGRIND_SCENE} --width 4 --height 4 --launches 1
                         OUTPUT "primary: 256 rays .* 0 mismatched.*shadow: .* 0 mismatched.*diffuse: .* 0 mismatched")
    set_tests_properties(oclgrind.cpu_code.bench_rays.bvh PROPERTIES
                         ENVIRONMENT "CLPATH_CACHE_DIR=off;CLPATH_KERNEL_CODE=cpu")
endif()
