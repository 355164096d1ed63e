# tirpol_cxx_sources(<out> <source dir>): every C++ source and header of the modules, apps, tests,
# bench, fuzz, python and examples, for the -P checks that read them all (CheckFormat.cmake,
# CheckTrackerNumbers.cmake). Fails when it finds so few that SOURCE_DIR must be wrong.
function(tirpol_cxx_sources out source_dir)
  set(sources)
  foreach(dir core calibration acquisition materials thermal simulation fitting report sweep live twin apps tests
              bench fuzz python examples)
    file(GLOB_RECURSE found "${source_dir}/${dir}/*.cpp" "${source_dir}/${dir}/*.h")
    list(APPEND sources ${found})
  endforeach()
  list(LENGTH sources count)
  if(count LESS 100)
    message(FATAL_ERROR "only ${count} C++ files found under ${source_dir}: wrong SOURCE_DIR?")
  endif()
  set(${out} ${sources} PARENT_SCOPE)
endfunction()
