# render --denoise (Open Image Denoise, loaded at run time).
set(DENOISE_OUT ${CMAKE_BINARY_DIR}/cli-test-out/denoise)
add_test(NAME cli.denoise_writes_twins_estimate_unchanged
         COMMAND ${CMAKE_COMMAND} -DCLPATH=$<TARGET_FILE:clpath> -DOUT=${DENOISE_OUT}
                 "-DARGS=render;--spp;4;--width;48;--height;36" -P ${CMAKE_CURRENT_SOURCE_DIR}/cli/denoise_outputs.cmake)
set_tests_properties(cli.denoise_writes_twins_estimate_unchanged PROPERTIES ENVIRONMENT "${CLPATH_TEST_ENV}"
                     TIMEOUT 300 SKIP_REGULAR_EXPRESSION "SKIPPED: Open Image Denoise is not installed")
# The library missing: a clear message naming what was tried and how to
# install it, exit status 1 (a run that cannot be done, like a missing
# device), before anything renders or is written.
add_test(NAME cli.denoise_missing_library
         COMMAND ${CMAKE_COMMAND} "-DCMD=$<TARGET_FILE:clpath>;render;--spp;1;--width;8;--height;8;--denoise;-o;${CLI_OUT}/no-oidn.png"
                 -DEXPECT_FAIL=1 -DEXPECT_RC=1 -DFORBID_FILE=${CLI_OUT}/no-oidn.png
                 "-DEXPECT_OUTPUT=--denoise: denoising needs Intel Open Image Denoise 2, and CLPATH_OIDN_LIBRARY=${CLI_OUT}/no-such-oidn.so does not load it:.*no-such-oidn\\.so: cannot open shared object file.*install it with tools/install-deps\\.sh"
                 "-DREJECT_OUTPUT=progress:"
                 -P ${CMAKE_CURRENT_SOURCE_DIR}/cli/expect.cmake)
set_tests_properties(cli.denoise_missing_library PROPERTIES TIMEOUT 60
                     ENVIRONMENT "${CLPATH_TEST_ENV};CLPATH_OIDN_LIBRARY=${CLI_OUT}/no-such-oidn.so")
