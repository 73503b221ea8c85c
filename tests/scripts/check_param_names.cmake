# SPDX-License-Identifier: MIT
# check_param_names.cmake — a method parameter's name is its field's name
# (docs/ARCHITECTURE.md "Adding a method"): every snell_param_info row in
# src/methods/ reads {.name = "F", .offset = offsetof(snell_glass_material, M.F)},
# so the name a CLI or snell_glass_set_param takes is the one a C user writes.
# Run: cmake -DSRC=<src dir> -P check_param_names.cmake
cmake_minimum_required(VERSION 3.25)
set(bad "")
set(rows 0)
file(GLOB files ${SRC}/methods/*.c)
foreach(f IN LISTS files)
  file(READ ${f} text)
  file(RELATIVE_PATH rel ${SRC} ${f})
  # every offsetof into the material must be part of a row this check reads
  string(REGEX MATCHALL "offsetof\\(snell_glass_material," all "${text}")
  string(REGEX MATCHALL "\\.name = \"[a-z0-9_]+\",[ \n]*\\.offset = offsetof\\(snell_glass_material, [a-z0-9_]+\\.[a-z0-9_]+\\)"
         found "${text}")
  list(LENGTH all n_all)
  list(LENGTH found n_found)
  if(NOT n_all EQUAL n_found)
    string(APPEND bad "  ${rel}: ${n_all} offsetof(snell_glass_material, ...) but ${n_found} rows of the form "
                      "{.name = \"F\", .offset = offsetof(snell_glass_material, M.F)}\n")
  endif()
  foreach(row IN LISTS found)
    string(REGEX REPLACE "^\\.name = \"([a-z0-9_]+)\".*" "\\1" name "${row}")
    string(REGEX REPLACE ".*, [a-z0-9_]+\\.([a-z0-9_]+)\\)$" "\\1" field "${row}")
    math(EXPR rows "${rows} + 1")
    if(NOT name STREQUAL field)
      string(APPEND bad "  ${rel}: parameter \"${name}\" sets field ${field}\n")
    endif()
  endforeach()
endforeach()
if(rows EQUAL 0)
  message(FATAL_ERROR "check_param_names: no parameter rows found under ${SRC}/methods")
endif()
if(bad)
  message(FATAL_ERROR "check_param_names: a parameter's name must be its field's name:\n${bad}")
endif()
message(STATUS "check_param_names: ${rows} parameters, each named as its field")
