# The tests that take longer than about 15 s on a 2-core machine (PoCL, warm
# kernel cache), labelled `slow` besides their kind (README, "Tests"), so that
# `ctest -L unit` stays under a minute and `ctest -LE slow` gives a quick pass.
#   clpath_slow_tests(TEST_PROGRAM Suite.Case ...)   cases of a tests/*/*_test.cpp program
#   clpath_slow_tests(KIND test ...)                 tests configured under tests/ (KIND: cli, viewer, oclgrind)
# Measured with `ctest -j2` on the 2-core EPYC VM; the time is each test's own.
clpath_slow_tests(presentation_test  # 11-16 s each: renders of a bare mesh with and without the sun
    PresentationRender.BareMeshShowsModelGroundAndShadow PresentationRender.ControlWithoutTheSunHasNoShadow
    PresentationRender.BareGltfShowsModelGroundAndShadow PresentationRender.GltfControlWithoutTheSunHasNoShadow)
clpath_slow_tests(convergence_test Convergence.MseFallsAsOneOverSpp)  # 12 s
clpath_slow_tests(reference_agreement_test  # 11-30 s
    ReferenceAgreement.EveryEntryAgrees ReferenceAgreement.RejectsAWrongImage ReferenceAgreement.CrossDevice)
clpath_slow_tests(light_transport_hard_test LightTransportHard.SkyOutsideClosedRoomChangesNothing)  # 24 s
clpath_slow_tests(cli bench.feature_cost_quick)  # 56 s
clpath_slow_tests(viewer_session  # the viewer's sessions (where Xvfb is installed): 10-24 s
    viewer.Session.ScreenshotAgreesWithRenderOfTheSameCamera viewer.Session.ResizedViewRendersLikeOneOpenedAtThatSize
    viewer.Session.KeysSwitchTheViewAndExposure)
# The fuzz tests (10-16 s each) are `fuzz;slow` in tests/fuzz/CMakeLists.txt.
clpath_slow_tests(obj_mesh_test ObjMesh.MillionTrianglesLoadInSeconds)  # 5-8 s: writes and loads a 1M-triangle OBJ
