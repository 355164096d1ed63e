# cmake -DSOURCE_DIR=<tree> -P CheckPublicHeaderUse.cmake
#
# Fails when a public header (<module>/include/**) is used only inside its own module: included by
# no other module, no test of another module, and none of apps/, python/, examples/ (directly, or
# through another public header of its module that is used). Such a header belongs in
# <module>/src/. Benchmarks (bench/) and fuzz targets (fuzz/) are no users: like a module's own
# tests they are white-box harnesses that see its src/ (bench/CMakeLists.txt, fuzz/CMakeLists.txt).
# Run by CTest (architecture.public_headers_used), so the public surface stays what users call.
# Count: find */include -name '*.h' | wc -l

cmake_minimum_required(VERSION 3.20)

if(NOT SOURCE_DIR)
  message(FATAL_ERROR "CheckPublicHeaderUse.cmake: pass -DSOURCE_DIR=<source tree>")
endif()

# Public headers, by the path a source includes them with, and the module that owns each.
set(public)
file(GLOB module_includes LIST_DIRECTORIES true ${SOURCE_DIR}/*/include)
foreach(root ${module_includes})
  get_filename_component(module_dir ${root} DIRECTORY)
  get_filename_component(module ${module_dir} NAME)
  file(GLOB_RECURSE headers RELATIVE ${root} ${root}/*.h)
  foreach(header ${headers})
    list(APPEND public ${header})
    string(MAKE_C_IDENTIFIER "${header}" key)
    set(owner_${key} ${module})
    set(path_${key} ${root}/${header})
  endforeach()
endforeach()
list(LENGTH public public_count)
if(public_count EQUAL 0)
  message(FATAL_ERROR "CheckPublicHeaderUse.cmake: no public header under ${SOURCE_DIR}/*/include")
endif()

# Every source and header of the tree but the harnesses (not build folders, which hold a
# CMakeCache.txt).
set(sources)
file(GLOB top_entries LIST_DIRECTORIES true ${SOURCE_DIR}/*)
foreach(entry ${top_entries})
  get_filename_component(name ${entry} NAME)
  if(IS_DIRECTORY ${entry} AND NOT EXISTS ${entry}/CMakeCache.txt AND NOT name MATCHES "^\\."
     AND NOT name MATCHES "^(bench|fuzz)$")
    file(GLOB_RECURSE found ${entry}/*.h ${entry}/*.cpp ${entry}/*.hpp ${entry}/*.cc)
    list(APPEND sources ${found})
  endif()
endforeach()

# The module a file belongs to: its top folder, or <name> for tests/<name>/.
function(owner_of file out)
  file(RELATIVE_PATH relative ${SOURCE_DIR} ${file})
  string(REPLACE "/" ";" parts "${relative}")
  list(GET parts 0 top)
  list(LENGTH parts depth)
  if(top STREQUAL "tests" AND depth GREATER 2)
    list(GET parts 1 top)
  endif()
  set(${out} ${top} PARENT_SCOPE)
endfunction()

function(included_headers file out)
  file(STRINGS ${file} lines REGEX "^[ \t]*#[ \t]*include[ \t]*[\"<]tirpol/")
  set(result)
  foreach(line ${lines})
    string(REGEX REPLACE "^[ \t]*#[ \t]*include[ \t]*[\"<]([^\">]+)[\">].*$" "\\1" included "${line}")
    list(APPEND result ${included})
  endforeach()
  set(${out} ${result} PARENT_SCOPE)
endfunction()

set(used)
foreach(file ${sources})
  owner_of(${file} file_owner)
  included_headers(${file} headers)
  foreach(header ${headers})
    string(MAKE_C_IDENTIFIER "${header}" key)
    if(DEFINED owner_${key} AND NOT owner_${key} STREQUAL file_owner)
      list(APPEND used ${header})
    endif()
  endforeach()
endforeach()
list(REMOVE_DUPLICATES used)

# A used public header makes the public headers it includes used too.
set(queue ${used})
while(queue)
  list(POP_FRONT queue header)
  string(MAKE_C_IDENTIFIER "${header}" key)
  included_headers(${path_${key}} headers)
  foreach(included ${headers})
    string(MAKE_C_IDENTIFIER "${included}" included_key)
    if(DEFINED owner_${included_key} AND NOT included IN_LIST used)
      list(APPEND used ${included})
      list(APPEND queue ${included})
    endif()
  endforeach()
endwhile()

set(unused)
foreach(header ${public})
  if(NOT header IN_LIST used)
    string(MAKE_C_IDENTIFIER "${header}" key)
    list(APPEND unused "${owner_${key}}/include/${header}")
  endif()
endforeach()
if(unused)
  list(JOIN unused "\n  " text)
  message(FATAL_ERROR "Public headers used only inside their own module (move them to the module's "
                      "src/; its tests see src/ too):\n  ${text}")
endif()
message(STATUS "${public_count} public headers, each used outside its module")
