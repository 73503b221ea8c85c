# SPDX-License-Identifier: MIT
cmake_policy(SET CMP0009 NEW)
# check_spdx.cmake — every source file of the tree carries the licence tag
# "SPDX-License-Identifier: MIT" in its first three lines (after a #! or
# <?xml line): C, C++, headers, shaders, CMake, scripts, build templates.
# Build trees (any folder named build*) and Python caches are left out.
# Run: cmake -DSOURCE_DIR=<repository root> -P check_spdx.cmake
set(patterns *.c *.h *.cpp *.glsl *.frag *.vert *.cmake CMakeLists.txt *.sh *.py *.in *.gradle *.map *.supp
    *.properties *.conf AndroidManifest.xml)
set(globs "")
foreach(p IN LISTS patterns)
  list(APPEND globs "${SOURCE_DIR}/${p}")
endforeach()
file(GLOB_RECURSE files LIST_DIRECTORIES false RELATIVE "${SOURCE_DIR}" ${globs})
list(APPEND files .ci/run)
set(missing "")
set(count 0)
foreach(f IN LISTS files)
  if(f MATCHES "(^|/)build[^/]*/" OR f MATCHES "__pycache__/|^\\.git/")
    continue()
  endif()
  if(NOT EXISTS "${SOURCE_DIR}/${f}")
    continue()
  endif()
  file(STRINGS "${SOURCE_DIR}/${f}" head LIMIT_COUNT 3)
  if(NOT head MATCHES "SPDX-License-Identifier: MIT")
    string(APPEND missing "\n  ${f}")
  endif()
  math(EXPR count "${count} + 1")
endforeach()
if(count LESS 300)
  message(FATAL_ERROR "only ${count} source files found under ${SOURCE_DIR}: is SOURCE_DIR the repository root?")
endif()
if(missing)
  message(FATAL_ERROR "no \"SPDX-License-Identifier: MIT\" in the first three lines of:${missing}")
endif()
message(STATUS "${count} source files carry the SPDX tag")
