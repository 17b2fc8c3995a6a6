# clpath export --format embree, then Embree's own pathtracer on the script it wrote:
#   cmake -DCLPATH=clpath -DSCENE=scene.json -DOUT=folder [-DPATHTRACER=pathtracer] -P embree_export.cmake
# Checks the script's camera, light and path length lines; with PATHTRACER (Debian's embree-tools),
# that Embree reads the script and the OBJ and writes an image.
file(REMOVE_RECURSE ${OUT})
execute_process(COMMAND ${CLPATH} export ${SCENE} ${OUT}/scene.ecs --format embree --max-depth 4
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}${err}")
if(NOT rc EQUAL 0)
    message(FATAL_ERROR "clpath export exited ${rc}")
endif()
foreach(f scene.ecs scene.obj scene.mtl)
    if(NOT EXISTS ${OUT}/${f})
        message(FATAL_ERROR "${OUT}/${f} was not written")
    endif()
endforeach()
file(READ ${OUT}/scene.ecs ecs)
foreach(line "-i scene.obj" "--vp 278 273 -800" "--vi 278 273 0" "--size 512 512"
             "--pointlight 278 448.799988 279.600006 155000 109500 36500" "--max-path-length 4")
    string(FIND "${ecs}" "\n${line}\n" at)
    if(at LESS 0)
        message(FATAL_ERROR "scene.ecs has no line '${line}':\n${ecs}")
    endif()
endforeach()
if(PATHTRACER)
    execute_process(COMMAND ${PATHTRACER} -c ${OUT}/scene.ecs --size 16 16 --spp 1 --threads 1 -o ${OUT}/embree.ppm
                    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
    message("${out}${err}")
    if(NOT rc EQUAL 0 OR NOT EXISTS ${OUT}/embree.ppm OR "${out}${err}" MATCHES "Error")
        message(FATAL_ERROR "Embree's pathtracer did not render the exported scene (exit ${rc})")
    endif()
else()
    message("Embree's pathtracer is not installed (Debian: embree-tools): only the export was checked")
endif()
