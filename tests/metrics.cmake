# SPDX-License-Identifier: MIT
# Error metrics (src/ref/metrics.c, include/snell/snell_metrics.h).
snell_add_test(test_metrics SOURCES test_metrics.c LABELS "unit")
target_link_libraries(test_metrics PRIVATE m)
