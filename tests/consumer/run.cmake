# Installs the build tree into a scratch prefix other than the configured one,
# moves it (a package must not remember where it was installed), then builds
# and runs consumers against it as users would:
#   consumer_shared, consumer_static   find_package(snell), a C-only project;
#                                      the static one loads a .glb (C++ inside)
#   consumer_pc, consumer_pc_static    cc with `pkg-config [--static] snell`
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
pkg_config(static_libs --static --libs)
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
message(STATUS "pkg-config snell: ${cflags} ${libs}; --static: ${static_libs}")
execute_process(COMMAND ${CC} ${SOURCE_DIR}/tests/consumer/main.c ${cflags} ${libs} -Wl,-rpath,${libdir}
                        -o ${WORK_DIR}/consumer_pc RESULT_VARIABLE rc)
if(rc)
  message(FATAL_ERROR "cc with `pkg-config --cflags --libs snell` failed: ${rc}")
endif()
run_consumer(${WORK_DIR}/consumer_pc)
# Static: libsnell.a, then what Libs.private and Requires.private add.
list(TRANSFORM static_libs REPLACE "^-lsnell$" "-Wl,-Bstatic;-lsnell;-Wl,-Bdynamic")
execute_process(COMMAND ${CC} ${SOURCE_DIR}/tests/consumer/main.c ${cflags} ${static_libs}
                        -o ${WORK_DIR}/consumer_pc_static RESULT_VARIABLE rc)
if(rc)
  message(FATAL_ERROR "cc with `pkg-config --static --cflags --libs snell` failed: ${rc}")
endif()
run_consumer(${WORK_DIR}/consumer_pc_static)
