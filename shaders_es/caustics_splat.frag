// caustics_splat.frag - a photon's share for this texel of its 2 x 2 point:
// the bilinear weights of the four texel centres about the photon, which sum
// to 1 (caustics_photon.vert), added into the receiver's light map.
precision highp float;

in vec4 v_flux;
layout(location = 0) out vec4 o_color;

void main()
{
    vec2 d = abs(gl_PointCoord * 2.0 - 1.0);
    o_color = v_flux * (1.0 - d.x) * (1.0 - d.y);
}
