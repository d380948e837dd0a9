# The training of LUZ_PGO (cmake/pgo.cmake), run as cmake -P with SOURCE_DIR, PGO_DIR, GENERATOR,
# CXX, NATIVE (LUZ_NATIVE) and PIC (position-independent code): an instrumented luz of the same
# sources and flags, then short renders of scenes that no benchmark times (the three pipelines,
# the antialiasing modes, glass and mirrors, a mesh through the BVH, shapes in its lanes), a few
# seconds.
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
# A mesh through the BVH that is neither the bunny nor the big mesh of the benchmarks: the bumpy
# sphere of scripts/make_big_mesh.py at 96 segments (9 024 triangles), in glass beside a mirror.
find_program(python3 NAMES python3 REQUIRED)
execute_process(COMMAND ${python3} ${SOURCE_DIR}/scripts/make_big_mesh.py 96
                OUTPUT_FILE ${PGO_DIR}/train/bumpy.obj COMMAND_ERROR_IS_FATAL ANY)
file(WRITE ${PGO_DIR}/train/mesh.json [=[{
  "image": {"width": 320, "height": 240},
  "camera": {"position": [0, 1.8, 4.5], "look_at": [0, 0.8, 0], "fov_y": 40},
  "render": {"pipeline": "raytrace", "max_depth": 5},
  "lights": [{"position": [-4, 6, 5], "intensity": 10}, {"position": [5, 3, 6], "intensity": 4}],
  "materials": {"floor": {"kd": 0.5, "ks": 0, "checker": {"size": 1, "kd": 0.3}},
                "mirror": {"preset": "metal_polido", "reflection": 0.8}},
  "objects": [
    {"type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0], "material": "floor"},
    {"type": "mesh", "file": "bumpy.obj", "smooth": true, "material": "vidro",
     "transform": {"scale": 0.8, "translate": [0.6, 0.85, 0.4]}},
    {"type": "sphere", "center": [-1.3, 0.7, -0.8], "radius": 0.7, "material": "mirror"}
  ]
}]=])

# Shapes in the BVH's lanes (spheres, open cylinders, frusta) with many shadow rays: three SPD
# scenes at size factors no benchmark renders (bench/spd.sh times the SPD's files, balls 4,
# rings 7, tree 11; bench/spd_sizes.py balls 3–5, rings 5–10, tree 11–14), NFF read directly.
foreach(scene balls:2 rings:3 tree:8)
  string(REPLACE ":" ";" scene ${scene})
  list(GET scene 0 name)
  list(GET scene 1 size)
  execute_process(COMMAND ${python3} ${SOURCE_DIR}/bench/spd_gen.py ${scene} --out ${PGO_DIR}/train
                  OUTPUT_QUIET COMMAND_ERROR_IS_FATAL ANY)
  file(RENAME ${PGO_DIR}/train/${name}.nff ${PGO_DIR}/train/spd_${name}_${size}.nff)
endforeach()

# Not demo:whitted (bench/whitted_vs_povray.sh, aa_quality, cost_growth, mpi_scaling,
# python_overhead), the bunny (bench/bvh_vs_embree), the big mesh, demo:primitives through the
# zbuffer (`luz view --benchmark`) nor the SPD's .nff scenes at the sizes above.
set(runs
  "demo:materials --width 320 --height 240 -o materials.png"
  "demo:materials --width 160 --height 120 --aa adaptive -o materials_adaptive.exr"
  "demo:materials --pipeline zbuffer --width 320 --height 240 --aa grid -o materials_zbuffer.ppm"
  "demo:materials --pipeline raycast --width 160 --height 120 --aa adaptive -o materials_rc.png"
  "demo:primitives --pipeline raytrace --width 160 --height 120 --aa grid -o primitives_rt.pfm"
  "demo:primitives --pipeline raycast --width 320 --height 240 --aa adaptive -o primitives_rc.png"
  "demo:highlight --width 160 --height 120 --frames 0:4 -o highlight.png"
  "${SOURCE_DIR}/scenes/figures/terms.json --pipeline zbuffer --aa adaptive -o terms.png"
  "${SOURCE_DIR}/scenes/exploding_glass.json --width 96 --height 72 --max-depth 8 -o glass.png"
  "mesh.json -o mesh.png"
  "mesh.json --pipeline zbuffer --aa adaptive -o mesh_zbuffer.png"
  "spd_balls_2.nff --width 128 --height 128 -o balls.png"
  "spd_rings_3.nff --width 128 --height 128 -o rings.png"
  "spd_tree_8.nff --width 128 --height 128 -o tree.png")
foreach(run IN LISTS runs)
  separate_arguments(args UNIX_COMMAND "${run}")
  foreach(threads 1 2)
    execute_process(COMMAND ${luz} render ${args} --threads ${threads} --quiet
                    WORKING_DIRECTORY ${PGO_DIR}/train COMMAND_ERROR_IS_FATAL ANY)
  endforeach()
endforeach()
file(TOUCH ${PGO_DIR}/profile.stamp)
