# The training of LUZ_PGO (cmake/pgo.cmake), run as cmake -P with SOURCE_DIR, PGO_DIR, GENERATOR,
# CXX, NATIVE (LUZ_NATIVE) and PIC (position-independent code): an instrumented luz of the same
# sources and flags, then renders that exercise what users run — every demo scene, the three
# pipelines, the antialiasing modes, a mesh through the BVH — small enough to take a few seconds.
set(build ${PGO_DIR}/build)
set(profile ${PGO_DIR}/profile)
execute_process(
  COMMAND ${CMAKE_COMMAND} -S ${SOURCE_DIR} -B ${build} -G ${GENERATOR}
          -DCMAKE_CXX_COMPILER=${CXX} -DCMAKE_BUILD_TYPE=Release -DLUZ_PGO=OFF -DLUZ_NATIVE=${NATIVE}
          -DCMAKE_POSITION_INDEPENDENT_CODE=${PIC}
          -DLUZ_BUILD_TESTS=OFF -DLUZ_BUILD_BENCH=OFF -DLUZ_BUILD_PYTHON=OFF
          -DLUZ_BUILD_VIEWER=OFF -DLUZ_BUILD_MPI=OFF
          "-DCMAKE_CXX_FLAGS=-fprofile-generate=${profile} -fprofile-update=atomic -fprofile-prefix-path=${build}"
  OUTPUT_QUIET COMMAND_ERROR_IS_FATAL ANY)
execute_process(COMMAND ${CMAKE_COMMAND} --build ${build} --target luz COMMAND_ERROR_IS_FATAL ANY)
file(REMOVE_RECURSE ${profile} ${PGO_DIR}/train)
file(MAKE_DIRECTORY ${PGO_DIR}/train)

set(luz ${build}/luz)
set(runs
  "demo:whitted --width 640 --height 480 -o whitted.png"
  "demo:whitted --width 320 --height 240 --aa grid -o whitted_grid.png"
  "demo:whitted --width 320 --height 240 --aa adaptive -o whitted_adaptive.exr"
  "demo:materials --width 320 --height 240 -o materials.png"
  "demo:bunny --width 320 --height 240 -o bunny.png"
  "demo:primitives --width 640 --height 480 -o primitives.png"
  "demo:primitives --width 320 --height 240 --aa adaptive -o primitives_adaptive.png"
  "demo:primitives --pipeline raycast --width 320 --height 240 -o primitives_raycast.ppm"
  "demo:primitives --pipeline raytrace --width 320 --height 240 --aa grid -o primitives_rt.pfm"
  "demo:bunny --pipeline zbuffer --width 320 --height 240 -o bunny_zbuffer.png")
foreach(run IN LISTS runs)
  separate_arguments(args UNIX_COMMAND "${run}")
  foreach(threads 1 2)
    execute_process(COMMAND ${luz} render ${args} --threads ${threads} --quiet
                    WORKING_DIRECTORY ${PGO_DIR}/train COMMAND_ERROR_IS_FATAL ANY)
  endforeach()
endforeach()
file(TOUCH ${PGO_DIR}/profile.stamp)
