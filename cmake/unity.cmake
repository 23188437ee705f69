# Unity batches of a target's sources (IMPACTFE_UNITY_BUILD): the .cpp files of one directory are
# compiled together, IMPACTFE_UNITY_BATCH per compiler run, so that the headers every file
# includes (Eigen, fmt, GoogleTest, the model) are parsed and their templates instantiated and
# optimised once per batch instead of once per file.
#
# CMake's own UNITY_BUILD is not used: its batch files include the sources by absolute path, so
# two checkouts of the same commit (a clone, a git worktree) produce different batch files and
# share nothing in ccache. These batch files name each source relative to ROOT, found through an
# include directory that ccache's base_dir makes relative too. Batches are formed per directory in
# sorted order, so adding a file re-forms only the batches of its directory.
#
# impactfe_unity_sources(<out-var> <tag> <root> <source>...): <out-var> receives the batch files
# (under the current binary directory); ROOT must be an include directory of the target.
function(impactfe_unity_sources out tag root)
  set(keys "")
  foreach(source IN LISTS ARGN)
    file(RELATIVE_PATH rel "${root}" "${source}")
    get_filename_component(dir "${rel}" DIRECTORY)
    string(MAKE_C_IDENTIFIER "dir_${dir}" key)
    list(APPEND files_${key} "${rel}")
    list(APPEND keys ${key})
  endforeach()
  list(REMOVE_DUPLICATES keys)
  list(SORT keys)
  set(batches "")
  foreach(key IN LISTS keys)
    list(SORT files_${key})
    list(LENGTH files_${key} count)
    set(index 0)
    set(start 0)
    while(start LESS count)
      set(content "// Unity batch of ${tag} (cmake/unity.cmake): generated, do not edit.\n")
      math(EXPR stop "${start} + ${IMPACTFE_UNITY_BATCH}")
      if(stop GREATER count)
        set(stop ${count})
      endif()
      math(EXPR last "${stop} - 1")
      foreach(i RANGE ${start} ${last})
        list(GET files_${key} ${i} rel)
        string(APPEND content "#include \"${rel}\"\n")
      endforeach()
      set(batch "${CMAKE_CURRENT_BINARY_DIR}/unity/${tag}_${key}_${index}.cpp")
      # Rewritten only when its content changes: an unchanged batch keeps its object.
      file(CONFIGURE OUTPUT "${batch}" CONTENT "${content}" @ONLY)
      list(APPEND batches "${batch}")
      math(EXPR index "${index} + 1")
      set(start ${stop})
    endwhile()
  endforeach()
  set(${out} ${batches} PARENT_SCOPE)
endfunction()
