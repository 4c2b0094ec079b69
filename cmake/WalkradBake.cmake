# walkrad_add_bake: bake a scene as a build step of a game's or app's CMake project.
#
#   include(path/to/walkrad/cmake/WalkradBake.cmake)
#   walkrad_add_bake(TARGET level1_lighting
#                    SCENE  ${CMAKE_CURRENT_SOURCE_DIR}/level1.glb
#                    VIEWS  ${CMAKE_CURRENT_SOURCE_DIR}/level1-walkthrough.json   # optional
#                    OUTPUT ${CMAKE_CURRENT_BINARY_DIR}/level1.bake
#                    OPTIONS --quality medium                                      # optional
#                    ALL)                                                          # optional
#
# The bake re-runs only when the scene, a file it refers to (buffers, images, MGF includes, IES
# profiles: the bake lists what it read in a depfile, `walkrad bake --depfile`), the walkthrough, the
# options or the walkrad executable change (the options are written to a stamp file that is rewritten
# only when they change, so this holds with Makefiles as well as Ninja; the depfile needs Ninja, or
# Makefiles with CMake 3.20 or later: other generators re-bake on the scene and DEPENDS only). walkrad writes the bake folder atomically: a failed or interrupted bake
# leaves the previous one in place. The executable is the `walkrad` target when walkrad is part of the
# build (add_subdirectory), else WALKRAD_EXECUTABLE (a cache variable, found on PATH by default).
function(walkrad_add_bake)
  cmake_parse_arguments(WB "ALL" "TARGET;SCENE;VIEWS;OUTPUT" "OPTIONS;DEPENDS" ${ARGN})
  foreach(required TARGET SCENE OUTPUT)
    if(NOT WB_${required})
      message(FATAL_ERROR "walkrad_add_bake: ${required} is required")
    endif()
  endforeach()
  if(TARGET walkrad)
    set(tool $<TARGET_FILE:walkrad>)
    set(tool_dep walkrad)
  else()
    find_program(WALKRAD_EXECUTABLE walkrad REQUIRED)
    set(tool ${WALKRAD_EXECUTABLE})
    set(tool_dep ${WALKRAD_EXECUTABLE})
  endif()

  set(command ${tool} bake ${WB_SCENE} -o ${WB_OUTPUT} --quiet)
  set(inputs ${WB_SCENE})
  if(WB_VIEWS)
    list(APPEND command --views ${WB_VIEWS})
    list(APPEND inputs ${WB_VIEWS})
  endif()
  list(APPEND command ${WB_OPTIONS})

  # The settings as a file: its time stamp changes only when its content does.
  set(stamp ${CMAKE_CURRENT_BINARY_DIR}/${WB_TARGET}.walkrad-settings)
  string(REPLACE ";" " " settings_text "${WB_SCENE}\n${WB_VIEWS}\n${WB_OPTIONS}")
  file(CONFIGURE OUTPUT ${stamp} CONTENT "${settings_text}\n")

  # What the scene refers to is known once it is read: the bake writes it as a depfile.
  set(depfile_args)
  if(CMAKE_GENERATOR MATCHES "Ninja" OR (CMAKE_GENERATOR MATCHES "Makefiles" AND NOT CMAKE_VERSION VERSION_LESS 3.20))
    set(depfile ${CMAKE_CURRENT_BINARY_DIR}/${WB_TARGET}.walkrad.d)
    list(APPEND command --depfile ${depfile})
    set(depfile_args DEPFILE ${depfile})
  endif()

  add_custom_command(
    OUTPUT ${WB_OUTPUT}/manifest.json
    COMMAND ${command}
    DEPENDS ${inputs} ${stamp} ${tool_dep} ${WB_DEPENDS}
    ${depfile_args}
    COMMENT "walkrad: baking ${WB_SCENE}"
    VERBATIM)
  if(WB_ALL)
    add_custom_target(${WB_TARGET} ALL DEPENDS ${WB_OUTPUT}/manifest.json)
  else()
    add_custom_target(${WB_TARGET} DEPENDS ${WB_OUTPUT}/manifest.json)
  endif()
  set_property(TARGET ${WB_TARGET} PROPERTY WALKRAD_BAKE_FOLDER ${WB_OUTPUT})
endfunction()
