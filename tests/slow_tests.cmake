# The tests that take over about 10 s in a -j2 run on a 2-core machine (PoCL),
# labelled `slow` beside their kind (README, "Tests"): `ctest -LE slow` gives a
# quick pass, and a unit program's slow cases stay out of `ctest -L unit`.
#   clpath_slow_tests(TEST_PROGRAM Suite.Case ...)   cases of a tests/*/*_test.cpp program
#   clpath_slow_tests(KIND test ...)                 tests configured under tests/ (KIND: cli, viewer, oclgrind)
# Seconds measured in -j2 runs of the whole suite on the 2-core EPYC VM while
# other builds shared it (warm kernel cache unless it says cold).
clpath_slow_tests(presentation_test  # 11-16 s cold, 2 s warm: the bare-mesh renders compile their own kernels
    PresentationRender.BareMeshShowsModelGroundAndShadow PresentationRender.ControlWithoutTheSunHasNoShadow
    PresentationRender.BareGltfShowsModelGroundAndShadow PresentationRender.GltfControlWithoutTheSunHasNoShadow)
clpath_slow_tests(convergence_test Convergence.MseFallsAsOneOverSpp)  # 12-23 s
clpath_slow_tests(adaptive_test Adaptive.ImageMeanIsUnbiasedAndABiasedRuleIsCaught)  # 19-25 s: 72 renders
clpath_slow_tests(gltf_layers_test GltfLayers.WhiteFurnaceNeverCreatesEnergy)  # 6-13 s: 180 cases x 100k samples
clpath_slow_tests(furnace_test WhiteFurnace.UniformHemisphere WhiteFurnace.ThesisDepthRussianRoulette)  # 7-13 s
clpath_slow_tests(reference_agreement_test  # 6-30 s
    ReferenceAgreement.EveryEntryAgrees ReferenceAgreement.RejectsAWrongImage ReferenceAgreement.CrossDevice)
clpath_slow_tests(light_transport_hard_test LightTransportHard.SkyOutsideClosedRoomChangesNothing)  # 21-24 s
clpath_slow_tests(hard_scenes_test HardScenes.EverySceneRendersFiniteAndScaleInvariant)  # 7-18 s
clpath_slow_tests(scale_test Scale.ImageMeanDoesNotDependOnTheDistance)  # 10-15 s
clpath_slow_tests(obj_mesh_test ObjMesh.MillionTrianglesLoadInSeconds)  # 5-8 s: writes and loads a 1M-triangle OBJ
clpath_slow_tests(cli bench.feature_cost_quick cli.scale.interrupt_checkpoint_resume)  # 24-56 s, 11-17 s
clpath_slow_tests(viewer_session  # the viewer's sessions (where Xvfb is installed): 10-46 s
    viewer.Session.ScreenshotAgreesWithRenderOfTheSameCamera viewer.Session.ResizedViewRendersLikeOneOpenedAtThatSize
    viewer.Session.KeysSwitchTheViewAndExposure)
# The fuzz tests (10-30 s each) are `fuzz;slow` in tests/fuzz/CMakeLists.txt.
# The light BVH against power in distribution, with controls (20-25 s each); both shapes with it forced on (55 s cold).
clpath_slow_tests(light_sampler_test LightSampler.TheLightBvhChangesNoExpectationUnderTheSky
    LightSampler.TheLightBvhChangesNoExpectationAmongManyLamps)
clpath_slow_tests(wavefront_test Wavefront.SameBitsWithTheLightBvh)
