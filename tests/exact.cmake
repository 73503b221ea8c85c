# Exact refraction by BVH traversal in the fragment shader (issue 18:
# src/methods/exact.c, shaders_es/exact.frag): exit directions vs the MATCHED
# reference on sphere, torus, goblet, an open real mesh (cat) and the bunny,
# both node formats; colour with absorption; the node budget's fallback and
# its count; AUTO's opt-in; one BVH per mesh version.
snell_add_test(test_exact SOURCES test_exact.c LABELS "render;gl" SHADINGS forward screen)
target_link_libraries(test_exact PRIVATE m)
