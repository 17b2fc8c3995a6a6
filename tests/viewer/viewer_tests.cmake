# Tests of the viewer (host/viewer).
#
# Its input logic (camera, script, keys, BVH boxes, pacing) is plain C++:
# tests/viewer/*_test.cpp, made into programs by tests/CMakeLists.txt like
# every module's, link those sources from the library below; they need no
# window and build even where the viewer is off.
#
# The sessions (viewer_session.cpp, named so that the *_test.cpp glob skips
# it) run the clpath program under xvfb-run: Xvfb with Mesa's llvmpipe, real
# kernels on the test device. They take one X server each, so they run one
# at a time (RESOURCE_LOCK): xvfb-run -a can race when started together.
set(CLPATH_VIEWER_LOGIC keymap camera_controller camera_snippet frame_pacer bvh_boxes view_script focus_pick
    denoise_pacing)
list(TRANSFORM CLPATH_VIEWER_LOGIC PREPEND ${CMAKE_SOURCE_DIR}/host/viewer/)
list(TRANSFORM CLPATH_VIEWER_LOGIC APPEND .cpp)
add_library(clpath_viewer_logic STATIC ${CLPATH_VIEWER_LOGIC})
target_link_libraries(clpath_viewer_logic PUBLIC clpath_core)
foreach(t camera_controller_test view_script_test viewer_logic_test)
    target_link_libraries(${t} PRIVATE clpath_viewer_logic)
endforeach()

if(CLPATH_WITH_VIEWER AND CLPATH_VIEWER_SOURCES)
    find_program(XVFB_RUN xvfb-run)
    if(XVFB_RUN)
        add_executable(viewer_session viewer/viewer_session.cpp viewer/block_agreement.cpp)
        target_link_libraries(viewer_session PRIVATE clpath_test_support GTest::gtest_main)
        target_compile_definitions(viewer_session PRIVATE "CLPATH_EXE=\"$<TARGET_FILE:clpath>\""
                                   "XVFB_RUN=\"${XVFB_RUN}\"" "VIEWER_TEST_OUT=\"${CMAKE_BINARY_DIR}/viewer-test-out\"")
        add_dependencies(viewer_session clpath)
        clpath_discover_tests(viewer_session viewer TEST_PREFIX viewer. DISCOVERY_TIMEOUT 60
                              PROPERTIES ENVIRONMENT "${CLPATH_TEST_ENV}" TIMEOUT 600 RESOURCE_LOCK xvfb)
    else()
        message(WARNING "xvfb-run not found: the viewer's session tests are left out (Debian: apt install xvfb)")
    endif()

    # No display: a message and a non-zero exit, not a crash.
    add_test(NAME viewer.no_display
             COMMAND ${CMAKE_COMMAND} -E env --unset=DISPLAY --unset=WAYLAND_DISPLAY
                     ${CMAKE_COMMAND} "-DCMD=$<TARGET_FILE:clpath>;view;--frames;1" -DEXPECT_FAIL=1
                     "-DEXPECT_OUTPUT=clpath: error: cannot open a window.*xvfb-run"
                     -P ${CMAKE_CURRENT_SOURCE_DIR}/cli/expect.cmake)
    # A bad script is refused before any window opens, naming the line.
    set(bad_script ${CMAKE_BINARY_DIR}/viewer-test-out/bad_script.txt)
    file(WRITE ${bad_script} "wait 1\njump 3\n")
    add_test(NAME viewer.bad_script
             COMMAND ${CMAKE_COMMAND} "-DCMD=$<TARGET_FILE:clpath>;view;--script;${bad_script}" -DEXPECT_FAIL=1
                     "-DEXPECT_OUTPUT=clpath: error: .*bad_script.txt:2: unknown command 'jump'"
                     -P ${CMAKE_CURRENT_SOURCE_DIR}/cli/expect.cmake)
    set_tests_properties(viewer.no_display viewer.bad_script PROPERTIES ENVIRONMENT "${CLPATH_TEST_ENV}" TIMEOUT 120)
endif()
