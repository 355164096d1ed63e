# tirpol_write_module_graph(<file>)
#
# Writes one line "<module>: <the tirpol modules it links directly, sorted>" for every module added
# by tirpol_add_module, from the targets' own link lists (PUBLIC and PRIVATE). ctest
# architecture.doc_modules reads it (cmake/CheckArchitectureDoc.cmake) and fails when the module
# table of docs/architecture.md lists other modules or other arrows.

include(TirpolProductionLinks)  # tirpol_plain_link_items

function(tirpol_write_module_graph file)
  get_property(modules GLOBAL PROPERTY TIRPOL_INSTALLED_MODULES)
  set(text "")
  foreach(module ${modules})
    get_target_property(links tirpol_${module} LINK_LIBRARIES)
    if(NOT links)
      set(links)
    endif()
    tirpol_plain_link_items(links ${links})
    set(deps)
    foreach(link ${links})
      if(link MATCHES "^tirpol(::|_)(.+)$" AND CMAKE_MATCH_2 IN_LIST modules)
        list(APPEND deps ${CMAKE_MATCH_2})
      endif()
    endforeach()
    list(REMOVE_DUPLICATES deps)
    list(SORT deps)
    list(JOIN deps " " joined)
    string(APPEND text "${module}: ${joined}\n")
  endforeach()
  file(WRITE ${file} "${text}")
endfunction()
