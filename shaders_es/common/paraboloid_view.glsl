// SPDX-License-Identifier: MIT
// paraboloid_view.glsl - an opaque object's fragments drawn straight into a
// dual-paraboloid map of a dynamic environment (SNELL_PARABOLOID_VIEW,
// opaque_paraboloid.vert), lit or not (opaque.frag, caustics_opaque.frag):
// farther behind the map's hemisphere than any texel the look-up reads (the
// rim's margin ring, z > -0.13 for maps of 32 texels and more) the
// projection held finite there is not the direction's: dropped.
#ifdef SNELL_PARABOLOID_VIEW
in highp float v_hemisphere; // opaque_paraboloid.vert
#endif

void snell_paraboloid_clip()
{
#ifdef SNELL_PARABOLOID_VIEW
    if (v_hemisphere < -0.2) discard;
#endif
}
