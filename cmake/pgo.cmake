# Profile-guided optimisation of the release build (LUZ_PGO, on in the `release` preset).
# The first build of a build folder first builds an instrumented `luz` of the same sources in
# <build>/pgo/build, runs cmake/pgo_train.cmake's renders with it (scenes no benchmark times,
# through the pipelines and antialiasing modes, a few seconds), and then compiles everything
# with the profile it wrote to <build>/pgo/profile. Functions the renders never ran are
# optimised as without a profile (-fprofile-partial-training). No floating-point option
# changes: the images are the same bits as without PGO. Delete <build>/pgo to train again after
# large changes; every object then compiles again with the new profile. A stale profile is only
# less useful: source changes are ignored with their warning silenced, and counts a change made
# inconsistent (code newly inlined into a function the profile knows) are smoothed by
# -fprofile-correction, where GCC would stop with "corrupted profile info"; so are the counts two
# training threads raced on.
if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
  message(FATAL_ERROR "LUZ_PGO needs GCC (its -fprofile-use and -fprofile-prefix-path)")
endif()
if(LUZ_SANITIZE)
  message(FATAL_ERROR "LUZ_PGO and LUZ_SANITIZE do not go together")
endif()

set(luz_pgo_dir ${PROJECT_BINARY_DIR}/pgo)
set(luz_pgo_stamp ${luz_pgo_dir}/profile.stamp)
# The profile files are named by the object's path within its build folder (prefix-path), so the
# training build's CMakeFiles/luz_render.dir/… profiles are found by this build's same objects.
add_compile_options(-fprofile-use=${luz_pgo_dir}/profile -fprofile-prefix-path=${PROJECT_BINARY_DIR}
                    -fprofile-partial-training -fprofile-correction -Wno-missing-profile
                    -Wno-coverage-mismatch)
add_custom_command(
  OUTPUT ${luz_pgo_stamp}
  COMMAND ${CMAKE_COMMAND} -DSOURCE_DIR=${PROJECT_SOURCE_DIR} -DPGO_DIR=${luz_pgo_dir}
          -DGENERATOR=${CMAKE_GENERATOR} -DCXX=${CMAKE_CXX_COMPILER} -DNATIVE=${LUZ_NATIVE}
          -DPIC=$<BOOL:${CMAKE_POSITION_INDEPENDENT_CODE}>
          -P ${PROJECT_SOURCE_DIR}/cmake/pgo_train.cmake
  DEPENDS ${PROJECT_SOURCE_DIR}/cmake/pgo_train.cmake ${PROJECT_SOURCE_DIR}/scripts/make_big_mesh.py
          ${PROJECT_SOURCE_DIR}/bench/spd_gen.py
  COMMENT "PGO: building an instrumented luz and running the training renders"
  USES_TERMINAL)
add_custom_target(luz_pgo_profile DEPENDS ${luz_pgo_stamp})

# The targets whose objects need the profile before they compile (called once they exist), and
# compile again whenever it is trained again (deleting <build>/pgo retrains it): each C++ source
# of theirs depends on the profile's stamp (tests/package/pgo_rebuild_test.sh checks it).
function(luz_pgo_after_profile)
  foreach(target ${ARGN})
    if(TARGET ${target})
      add_dependencies(${target} luz_pgo_profile)
      get_target_property(dir ${target} SOURCE_DIR)
      get_target_property(sources ${target} SOURCES)
      foreach(source ${sources})
        if(source MATCHES "\\.(cpp|cc|cxx)$" AND NOT source MATCHES "^\\$<")
          cmake_path(ABSOLUTE_PATH source BASE_DIRECTORY ${dir})
          set_property(SOURCE ${source} TARGET_DIRECTORY ${target} APPEND
                       PROPERTY OBJECT_DEPENDS ${luz_pgo_stamp})
        endif()
      endforeach()
    endif()
  endforeach()
endfunction()
