# SPDX-License-Identifier: MIT
# check_kiosk_install.cmake — snell-kiosk ships as a service: installed to a
# scratch prefix, the systemd unit and the example configuration are there,
# the unit starts the installed kiosk with that configuration by the paths of
# that prefix, not the configured one (systemd-analyze verify, where there is
# one), and the installed kiosk previews that configuration off the device.
# Run: cmake -DBUILD_DIR= -DWORK_DIR= -P check_kiosk_install.cmake
file(REMOVE_RECURSE ${WORK_DIR})
execute_process(COMMAND ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${WORK_DIR}/prefix
                RESULT_VARIABLE rc OUTPUT_QUIET)
if(rc)
  message(FATAL_ERROR "install failed: ${rc}")
endif()
set(p ${WORK_DIR}/prefix)
set(unit ${p}/lib/systemd/system/snell-kiosk.service)
set(conf ${p}/etc/snell/kiosk.conf)
foreach(f ${unit} ${conf} ${p}/bin/snell-kiosk)
  if(NOT EXISTS ${f})
    message(FATAL_ERROR "not installed: ${f}")
  endif()
endforeach()
file(READ ${unit} text)
if(NOT text MATCHES "\nExecStart=${p}/bin/snell-kiosk --config ${p}/etc/snell/kiosk.conf\n" OR
   NOT text MATCHES "\nRestart=on-failure\n" OR NOT text MATCHES "\nRestartPreventExitStatus=2\n")
  message(FATAL_ERROR "${unit}: ExecStart, Restart or RestartPreventExitStatus not as expected:\n${text}")
endif()
find_program(SYSTEMD_ANALYZE systemd-analyze)
if(SYSTEMD_ANALYZE)
  file(WRITE ${WORK_DIR}/unit/snell-kiosk.service "${text}")
  execute_process(COMMAND ${SYSTEMD_ANALYZE} verify ${WORK_DIR}/unit/snell-kiosk.service
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(rc OR out MATCHES "snell-kiosk")
    message(FATAL_ERROR "systemd-analyze verify: ${out}")
  endif()
  message(STATUS "systemd-analyze verify: the unit is clean")
else()
  message(STATUS "no systemd-analyze: the unit's syntax not verified")
endif()
# The installed configuration, previewed by the installed kiosk (a small
# --mode after --config overrides the file's default size).
execute_process(COMMAND ${p}/bin/snell-kiosk --config ${conf} --mode 160x120 --preview ${WORK_DIR}/preview.png
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(rc OR NOT EXISTS ${WORK_DIR}/preview.png OR NOT out MATCHES "preview of cubemap:scene=bunny")
  message(FATAL_ERROR "snell-kiosk --config ${conf} --preview: exit ${rc}\n${out}${err}")
endif()
message(STATUS "${out}")
