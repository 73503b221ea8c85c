# 2D lightmap (lm2d) tests: unit (geometry, scene files, tracer, contour) and
# render (GL lines vs the exact rasteriser, showcase scenes) on llvmpipe.
foreach(t geom scene trace contour)
  if(EXISTS ${CMAKE_CURRENT_SOURCE_DIR}/test_lm2d_${t}.c)
    snell_add_test(test_lm2d_${t} SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/test_lm2d_${t}.c LABELS unit lm2d)
  endif()
endforeach()
foreach(t raster render)
  if(EXISTS ${CMAKE_CURRENT_SOURCE_DIR}/test_lm2d_${t}.c)
    snell_add_test(test_lm2d_${t} SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/test_lm2d_${t}.c LABELS render gl lm2d)
  endif()
endforeach()
