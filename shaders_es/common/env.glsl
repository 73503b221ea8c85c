// env.glsl - the environment's radiance along a direction (Unger 2.2.2: a
// cubemap indexed by direction only, the light from infinitely far). Every
// kernel looks the environment up through snell_env, so that another
// representation of it (or of what lies beyond the glass) changes one place.
uniform samplerCube u_env;

vec3 snell_env(vec3 dir)
{
    return texture(u_env, dir).rgb;
}
