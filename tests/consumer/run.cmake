# SPDX-License-Identifier: MIT
# Installs the build tree into a scratch prefix other than the configured one
# (the licence and third-party notices with it),
# moves it (a package must not remember where it was installed), then builds
# and runs consumers against it as users would:
#   consumer_shared, consumer_static   find_package(snell), a C-only project;
#                                      the static one loads a .glb (C++ inside)
#   consumer_gl                        its own EGL and GLES calls, linked
#                                      through snell::snell alone
#   consumer_pc                        cc with `pkg-config --cflags --libs snell`
#   consumer_pc_static[_flag]          the shell line `cc main.c $(pkg-config [--static]
#                                      --cflags --libs snell-static)`, and readelf -d
#                                      shows it does not need libsnell.so
# Each consumer renders a frame and loads GLB (tests/data/nodes.glb).
# Args: -DBUILD_DIR= -DSOURCE_DIR= -DWORK_DIR= -DCC= -DGLB=
file(REMOVE_RECURSE ${WORK_DIR})
execute_process(COMMAND ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${WORK_DIR}/staging
                RESULT_VARIABLE rc OUTPUT_QUIET)
if(rc)
  message(FATAL_ERROR "install failed: ${rc}")
endif()
file(RENAME ${WORK_DIR}/staging ${WORK_DIR}/prefix)
set(prefix ${WORK_DIR}/prefix)

# The licence, the third-party notices and their texts, as installed.
foreach(f LICENSE THIRD_PARTY.md LICENSES/stb.txt LICENSES/cglm.txt LICENSES/tinygltf.txt LICENSES/meshoptimizer.txt)
  if(NOT EXISTS ${prefix}/share/doc/snell/${f})
    message(FATAL_ERROR "not installed: share/doc/snell/${f}")
  endif()
endforeach()
file(READ ${prefix}/share/doc/snell/LICENSE text)
if(NOT text MATCHES "^MIT License\n")
  message(FATAL_ERROR "share/doc/snell/LICENSE is not the MIT licence:\n${text}")
endif()

function(run_consumer exe)
  execute_process(COMMAND ${exe} ${GLB} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out
                  OUTPUT_STRIP_TRAILING_WHITESPACE)
  if(rc)
    message(FATAL_ERROR "${exe} failed (${rc}): ${out}")
  endif()
  message(STATUS "${exe}: ${out}")
endfunction()

# --- CMake package ------------------------------------------------------------
execute_process(COMMAND ${CMAKE_COMMAND} -S ${SOURCE_DIR}/tests/consumer -B ${WORK_DIR}/build
                        -DCMAKE_PREFIX_PATH=${prefix} RESULT_VARIABLE rc)
if(rc)
  message(FATAL_ERROR "consumer configure failed: ${rc}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build ${WORK_DIR}/build RESULT_VARIABLE rc)
if(rc)
  message(FATAL_ERROR "consumer build failed: ${rc}")
endif()
run_consumer(${WORK_DIR}/build/consumer_shared)
run_consumer(${WORK_DIR}/build/consumer_static)
run_consumer(${WORK_DIR}/build/consumer_gl)

# --- pkg-config -------------------------------------------------------------------
file(GLOB pc ${prefix}/lib*/pkgconfig/snell.pc ${prefix}/lib/*/pkgconfig/snell.pc)
if(NOT pc)
  message(FATAL_ERROR "snell.pc not installed")
endif()
list(GET pc 0 pc)
get_filename_component(pcdir ${pc} DIRECTORY)
set(ENV{PKG_CONFIG_PATH} ${pcdir})
function(pkg_config out)
  execute_process(COMMAND pkg-config ${ARGN} snell OUTPUT_VARIABLE v RESULT_VARIABLE rc
                  OUTPUT_STRIP_TRAILING_WHITESPACE)
  if(rc)
    message(FATAL_ERROR "pkg-config ${ARGN} snell failed")
  endif()
  separate_arguments(v UNIX_COMMAND "${v}")
  set(${out} ${v} PARENT_SCOPE)
endfunction()
pkg_config(cflags --cflags)
pkg_config(libs --libs)
pkg_config(libdir --variable=libdir)
file(REAL_PATH ${prefix} real_prefix)
file(REAL_PATH ${libdir} real_libdir)
set(include_found 0)
foreach(flag IN LISTS cflags)
  if(flag MATCHES "^-I(.*)")
    file(REAL_PATH ${CMAKE_MATCH_1} dir)
    if(dir STREQUAL "${real_prefix}/include")
      set(include_found 1)
    endif()
  endif()
endforeach()
if(NOT include_found)
  message(FATAL_ERROR "snell.pc's Cflags do not point into the installed prefix ${prefix}: ${cflags}")
endif()
if(NOT real_libdir MATCHES "^${real_prefix}/")
  message(FATAL_ERROR "snell.pc's libdir ${libdir} is not under the installed prefix ${prefix}")
endif()
message(STATUS "pkg-config snell: ${cflags} ${libs}")
execute_process(COMMAND ${CC} ${SOURCE_DIR}/tests/consumer/main.c ${cflags} ${libs} -Wl,-rpath,${libdir}
                        -o ${WORK_DIR}/consumer_pc RESULT_VARIABLE rc)
if(rc)
  message(FATAL_ERROR "cc with `pkg-config --cflags --libs snell` failed: ${rc}")
endif()
run_consumer(${WORK_DIR}/consumer_pc)
# The shared libraries a program needs (readelf -d).
function(needed exe out)
  execute_process(COMMAND readelf -d ${exe} OUTPUT_VARIABLE d RESULT_VARIABLE rc)
  if(rc)
    message(FATAL_ERROR "readelf -d ${exe} failed (${rc})")
  endif()
  string(REGEX MATCHALL "\\(NEEDED\\)[^\n]*" n "${d}")
  set(${out} "${n}" PARENT_SCOPE)
endfunction()
needed(${WORK_DIR}/consumer_pc shared_needed)
if(NOT shared_needed MATCHES "libsnell\\.so")
  message(FATAL_ERROR "consumer_pc does not need libsnell.so (${shared_needed}): the static checks below would prove nothing")
endif()
# Static: snell-static.pc names libsnell.a and what it needs; typed as a user
# types it, in a shell, with and without --static.
foreach(flag "" "--static")
  string(REPLACE "-" "_" suffix "${flag}")
  set(exe ${WORK_DIR}/consumer_pc_static${suffix})
  set(line "${CC} ${SOURCE_DIR}/tests/consumer/main.c $(pkg-config ${flag} --cflags --libs snell-static) -o ${exe}")
  execute_process(COMMAND sh -c "${line}" RESULT_VARIABLE rc)
  if(rc)
    message(FATAL_ERROR "`${line}` failed: ${rc}")
  endif()
  run_consumer(${exe})
  needed(${exe} static_needed)
  if(static_needed MATCHES "libsnell")
    message(FATAL_ERROR "`${line}` links libsnell.so: ${static_needed}")
  endif()
  message(STATUS "${line}: runs, needs no libsnell.so")
endforeach()
