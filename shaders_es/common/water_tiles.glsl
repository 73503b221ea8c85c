// SPDX-License-Identifier: MIT
// water_tiles.glsl - the container's procedural tiles (GLSL twin of
// snell__water_tile, src/water/water_sim.c): squares of side u_water_tile_size from
// the container's corner, a checker of two colours with grout lines 5% of a
// tile wide; face 0 the floor, 1/2 the walls x = -+half, 3/4 z = -+half,
// walls 0.8 as bright as the floor.
uniform highp float u_water_half;       // container half width
uniform highp float u_water_depth;      // floor below the rest level
uniform highp float u_water_tile_size;

vec3 water_tile(int face, highp vec3 p)
{
    highp vec2 uv = face == 0 ? vec2(p.x + u_water_half, p.z + u_water_half)
                  : face <= 2 ? vec2(p.z + u_water_half, p.y + u_water_depth) : vec2(p.x + u_water_half, p.y + u_water_depth);
    uv /= u_water_tile_size;
    highp vec2 f = uv - floor(uv);
    vec3 c;
    if (f.x < 0.05 || f.y < 0.05 || f.x > 0.95 || f.y > 0.95) c = vec3(0.30, 0.30, 0.32);
    else if (mod(floor(uv.x) + floor(uv.y), 2.0) != 0.0) c = vec3(0.20, 0.42, 0.62);
    else c = vec3(0.92, 0.90, 0.82);
    return c * (face == 0 ? 1.0 : 0.8);
}
