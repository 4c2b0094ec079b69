# The pipeline's stages (docs/architecture.md): one folder and one static library each, declared in
# the order of the data flow. A stage may link only stages declared before it; walkrad_stage() stops
# the configuration otherwise, so a later stage's headers are never on an earlier stage's include path.
# walkrad_stage_forbid() states links a stage must not have even indirectly (the reference tracer's
# independence from the solvers). pipeline/stages.json in the build tree records the graph for the
# layout test (tests/layout/check_layout.py), which scans every #include against it; the rules here
# are tested on a scratch project (tests/layout/stage_rules).

# walkrad_stage(NAME SOURCES src... STAGES earlier-stage... PUBLIC lib... PRIVATE lib...)
function(walkrad_stage name)
  cmake_parse_arguments(S "" "" "SOURCES;STAGES;PUBLIC;PRIVATE" ${ARGN})
  get_property(declared GLOBAL PROPERTY WALKRAD_STAGES)
  foreach(dep IN LISTS S_STAGES)
    if(NOT dep IN_LIST declared)
      message(FATAL_ERROR "pipeline/${name} links stage '${dep}', which is not declared before it "
                          "(stages so far: ${declared}). A stage links only the stages before it.")
    endif()
  endforeach()
  add_library(walkrad_${name} STATIC ${S_SOURCES})
  target_include_directories(walkrad_${name} PUBLIC include)
  list(TRANSFORM S_STAGES PREPEND walkrad_ OUTPUT_VARIABLE stage_targets)
  target_link_libraries(walkrad_${name} PUBLIC ${stage_targets} ${S_PUBLIC} PRIVATE ${S_PRIVATE})
  walkrad_warnings(walkrad_${name})
  set_property(GLOBAL APPEND PROPERTY WALKRAD_STAGES ${name})
  set_property(GLOBAL PROPERTY WALKRAD_STAGE_DEPS_${name} ${S_STAGES})
endfunction()

# The stages `name` reaches through its links, itself excluded.
function(walkrad_stage_closure name out)
  set(todo ${name})
  set(seen "")
  while(todo)
    list(POP_FRONT todo s)
    get_property(deps GLOBAL PROPERTY WALKRAD_STAGE_DEPS_${s})
    foreach(d IN LISTS deps)
      if(NOT d IN_LIST seen)
        list(APPEND seen ${d})
        list(APPEND todo ${d})
      endif()
    endforeach()
  endwhile()
  set(${out} ${seen} PARENT_SCOPE)
endfunction()

# walkrad_stage_forbid(NAME stage... REASON text): NAME must not reach any of these stages.
function(walkrad_stage_forbid name)
  cmake_parse_arguments(F "" "REASON" "STAGES" ${ARGN})
  walkrad_stage_closure(${name} reached)
  foreach(s IN LISTS F_STAGES)
    if(s IN_LIST reached)
      message(FATAL_ERROR "pipeline/${name} links stage '${s}' (through ${reached}): ${F_REASON}")
    endif()
  endforeach()
endfunction()

# Writes <build>/pipeline/stages.json: {"order": [...], "deps": {stage: [...]}}.
function(walkrad_stages_write_json path)
  # A CMake list as a JSON array of strings.
  function(json_array list out)
    if(list)
      list(JOIN list "\", \"" joined)
      set(${out} "[\"${joined}\"]" PARENT_SCOPE)
    else()
      set(${out} "[]" PARENT_SCOPE)
    endif()
  endfunction()
  get_property(order GLOBAL PROPERTY WALKRAD_STAGES)
  json_array("${order}" order_json)
  set(deps_json "")
  foreach(s IN LISTS order)
    get_property(deps GLOBAL PROPERTY WALKRAD_STAGE_DEPS_${s})
    json_array("${deps}" a)
    list(APPEND deps_json "\"${s}\": ${a}")
  endforeach()
  list(JOIN deps_json ", " deps_json)
  file(WRITE ${path} "{\"order\": ${order_json}, \"deps\": {${deps_json}}}\n")
endfunction()

# walkrad_stage_tests(NAME SOURCES test... LINK extra-lib...): the stage's GoogleTest executable.
# Tests may drive a whole bake (LINK walkrad_bake) to reach their stage; the libraries may not. A stage's
# tests may read its private headers (src/): its parts are tested on their own, beside them.
function(walkrad_stage_tests name)
  cmake_parse_arguments(T "" "" "SOURCES;LINK" ${ARGN})
  add_executable(walkrad_${name}_tests ${T_SOURCES})
  target_link_libraries(walkrad_${name}_tests PRIVATE walkrad_${name} ${T_LINK} walkrad_testing GTest::gtest_main)
  target_compile_definitions(walkrad_${name}_tests PRIVATE WALKRAD_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
  target_include_directories(walkrad_${name}_tests PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}/src)
  walkrad_warnings(walkrad_${name}_tests)
  gtest_discover_tests(walkrad_${name}_tests DISCOVERY_TIMEOUT 60)
endfunction()
