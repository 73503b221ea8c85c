# snell-bench: time vs error of the refraction methods (snell_bench.c + bench_*.c);
# `snell-bench --2d` runs the 2D lightmap benchmarks of bench2d.c when present.
file(GLOB SNELL_BENCH_SOURCES CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/bench_*.c)
set(SNELL_BENCH_2D_SOURCE)
if(EXISTS ${CMAKE_CURRENT_SOURCE_DIR}/bench2d.c)
  set(SNELL_BENCH_2D_SOURCE ${CMAKE_CURRENT_SOURCE_DIR}/bench2d.c)
endif()
add_executable(snell-bench snell_bench.c ${SNELL_BENCH_SOURCES} ${SNELL_BENCH_2D_SOURCE})
target_link_libraries(snell-bench PRIVATE snell_static m)
target_compile_options(snell-bench PRIVATE ${SNELL_WARNINGS})
if(SNELL_BENCH_2D_SOURCE)
  target_compile_definitions(snell-bench PRIVATE SNELL_HAVE_BENCH2D=1)
endif()
install(TARGETS snell-bench RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})

# snell-render --trace-pixel (trace_pixel.c; the render*.c glob does not pick it up).
if(EXISTS ${CMAKE_CURRENT_SOURCE_DIR}/trace_pixel.c)
  target_sources(snell-render PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}/trace_pixel.c)
  target_compile_definitions(snell-render PRIVATE SNELL_HAVE_TRACE_PIXEL=1)
endif()
