# SPDX-License-Identifier: MIT
# Stress harness (issue 3, item 6): every method vs the reference across IOR,
# grazing views, mesh scale and thin shells; zero NaN/Inf, stated error bounds.
# One test per method so a failure names it: the methods of the registry this
# build holds (SNELL_METHODS_ON, read from src/methods/registry.c by
# cmake/components.cmake), so a new registry line brings its stress test; one
# without bounds in test_stress.c reports them as not stated (skipped).
# Configure with -DSNELL_FP16_EMULATION=ON in a separate build dir for the
# mediump study.
foreach(method IN LISTS SNELL_METHODS_ON)
  snell_add_test(test_stress_${method} SOURCES test_stress.c LABELS "stress;gl" ARGS ${method} TIMEOUT 240 SHADINGS forward screen)
  if(NOT TARGET test_stress_${method})
    continue() # left out with a component (the reference tracer)
  endif()
  target_link_libraries(test_stress_${method} PRIVATE m)
  if(SNELL_FP16_EMULATION)
    target_compile_definitions(test_stress_${method} PRIVATE SNELL_FP16_EMULATION=1)
  endif()
endforeach()
# exact with its FULL-model terms (material.exact fresnel, inner_fresnel,
# reentry) against MATCHED with the same snell_ref_terms.
if(TARGET test_stress_exact)
  snell_add_test(test_stress_exact_terms SOURCES test_stress.c LABELS "stress;gl" ARGS exact terms TIMEOUT 240)
  target_link_libraries(test_stress_exact_terms PRIVATE m)
endif()
